// uhi/lamp_response.csv: K(λ) per UHI band, band counting from 0, DN > 0.
#include "core/survey/lamp_response_csv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "tests/support/expect_input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::expectInputError;

TEST(LampResponseCsvTest, ReadsOneDnPerBand) {
  EXPECT_EQ(parseLampResponseCsv("band,dn\n0,1830.5\n1,2012\n2, 7e3 \r\n", "r.csv"),
            (std::vector<double>{1830.5, 2012.0, 7000.0}));
}

TEST(LampResponseCsvTest, WriteThenReadIsBitExact) {
  testing::TempFolder folder("lamp-response");
  const std::vector<double> dn = {1.0 / 3.0, 2012.0, 1e-300, 65535.123456789};
  writeLampResponseCsv(folder / "r.csv", dn);
  EXPECT_EQ(testing::readText(folder / "r.csv"),
            "band,dn\n0,0.3333333333333333\n1,2012\n2,1e-300\n3,65535.123456789\n");
  EXPECT_EQ(readLampResponseCsv(folder / "r.csv"), dn);
}

TEST(LampResponseCsvTest, WriterRefusesWhatTheReaderWouldRefuse) {
  testing::TempFolder folder("lamp-response-bad");
  EXPECT_THROW(writeLampResponseCsv(folder / "r.csv", {}), std::invalid_argument);
  EXPECT_THROW(writeLampResponseCsv(folder / "r.csv", {1.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(writeLampResponseCsv(folder / "r.csv", {std::nan("")}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(folder / "r.csv"));
}

TEST(LampResponseCsvTest, Errors) {
  expectInputError([] { parseLampResponseCsv("band,DN\n0,1\n", "r.csv"); }, "r.csv",
                   "line 1: expected the header 'band,dn', got 'band,DN'");
  expectInputError([] { parseLampResponseCsv("band,dn\n", "r.csv"); }, "r.csv",
                   "line 2: no data rows; expected at least one row after the header 'band,dn'");
  expectInputError([] { parseLampResponseCsv("band,dn\n1,100\n", "r.csv"); }, "r.csv",
                   "line 2: column 'band': expected band 0 (one row per UHI band, counting from 0 "
                   "in order), got 1");
  // A band that does not increase (repeated or going back) is out of order.
  expectInputError([] { parseLampResponseCsv("band,dn\n0,100\n1,110\n1,120\n", "r.csv"); },
                   "r.csv",
                   "line 4: column 'band': expected band 2 (one row per UHI band, counting from 0 "
                   "in order), got 1");
  expectInputError([] { parseLampResponseCsv("band,dn\n0,100\n1,0\n", "r.csv"); }, "r.csv",
                   "line 3: column 'dn': expected a DN > 0 (one lamp's response on a white "
                   "target at 1 m), got 0");
  expectInputError([] { parseLampResponseCsv("band,dn\n0,-5\n", "r.csv"); }, "r.csv",
                   "line 2: column 'dn': expected a DN > 0 (one lamp's response on a white "
                   "target at 1 m), got -5");
  expectInputError([] { parseLampResponseCsv("band,dn\n0,inf\n", "r.csv"); }, "r.csv",
                   "line 2: column 'dn': expected a finite number, got 'inf'");
  expectInputError([] { parseLampResponseCsv("band,dn\n0.5,1\n", "r.csv"); }, "r.csv",
                   "line 2: column 'band': expected an integer, got '0.5'");
  expectInputError([] { parseLampResponseCsv("band,dn\n0,1,2\n", "r.csv"); }, "r.csv",
                   "line 2: expected 2 columns (band,dn), got 3");
}

}  // namespace
}  // namespace hsmap
