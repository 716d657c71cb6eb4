#include "pipelines/report/named_csv.h"

#include <gtest/gtest.h>

#include "tests/support/expect_input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::expectInputError;
using testing::TempFolder;

TEST(NamedCsv, ReadsTheColumnsAskedForWhateverOtherColumnsTheFileHas) {
  TempFolder folder;
  const auto file = folder.write("keyframes.csv", "keyframe,frame,t,extra,x\n0,0,36000.515,a,1.5\n\n1,5,36000.715,b,-2\n");
  const NamedCsv table(file, {"t", "x"});
  ASSERT_EQ(table.rowCount(), 2u);
  EXPECT_EQ(table.number(0, "t"), 36000.515);
  EXPECT_EQ(table.number(1, "x"), -2.0);
  EXPECT_EQ(table.integer(1, "frame"), 5);
  EXPECT_EQ(table.text(1, "extra"), "b");
  EXPECT_EQ(table.lineNumber(1), 4);  // the blank line is skipped, not counted out
}

TEST(NamedCsv, AMissingColumnNamesTheFileTheHeaderAndTheColumn) {
  const std::filesystem::path file = "RUN/georef/rejected_fixes.csv";
  expectInputError([&] { NamedCsv("fix,t,offset_m\n0,1,2\n", file, {"fix", "ins_line"}); }, file,
                   "line 1: expected a column 'ins_line' in the header, got 'fix,t,offset_m'");
}

TEST(NamedCsv, ARowWithTheWrongCellCountNamesItsLine) {
  const std::filesystem::path file = "RUN/frontend/losses.csv";
  expectInputError([&] { NamedCsv("first_frame,last_frame,reason\n3,4,dark\n5,6\n", file, {"reason"}); }, file,
                   "line 3: expected 3 comma-separated cells (as the header), got 2");
}

TEST(NamedCsv, ACellThatIsNotANumberNamesItsLineAndColumn) {
  const std::filesystem::path file = "RUN/report/ortho_patches.csv";
  const NamedCsv table("north_m,east_m\n1.5,2\n1.5,abc\n", file, {"north_m", "east_m"});
  EXPECT_EQ(table.number(0, "east_m"), 2.0);
  expectInputError([&] { table.number(1, "east_m"); }, file, "line 3: column 'east_m': expected a number, got 'abc'");
  expectInputError([&] { table.integer(0, "north_m"); }, file,
                   "line 2: column 'north_m': expected an integer, got '1.5'");
}

TEST(NamedCsv, AnEmptyFileIsAnError) {
  const std::filesystem::path file = "RUN/frontend/losses.csv";
  expectInputError([&] { NamedCsv("", file, {}); }, file, " is empty; expected a header line");
}

}  // namespace
}  // namespace hsmap
