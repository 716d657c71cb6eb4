#include "core/survey/csv_table.h"

#include <gtest/gtest.h>

#include "core/util/input_error.h"
#include "tests/support/expect_input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::expectInputError;
using testing::TempFolder;
using testing::writeText;

class CsvTableTest : public ::testing::Test {
 protected:
  TempFolder folder_{"csv"};
  std::filesystem::path file(const std::string& name, const std::string& text) {
    const auto path = folder_ / name;
    writeText(path, text);
    return path;
  }
};

TEST_F(CsvTableTest, ReadsFramesLinesAndInsTables) {
  const auto frames = readFramesCsv(file("frames.csv", "file,t\na.png,10.5\nb.png,10.54\n"));
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].file, "b.png");
  EXPECT_EQ(frames[1].t, 10.54);
  EXPECT_EQ(frames[1].line_number, 3);

  const auto lines = readLinesCsv(file("lines.csv", "line,t\n0,1\n1,1.5\n2,2.25\n"));
  EXPECT_EQ(lines, (std::vector<double>{1.0, 1.5, 2.25}));

  const InsTable ins =
      readInsCsv(file("ins.csv", "t,lat,lon,depth\n0,43.1,5.2,10\n1,43.2,5.3,11\n"));
  EXPECT_FALSE(ins.has_attitude);
  ASSERT_EQ(ins.fixes.size(), 2u);
  EXPECT_EQ(ins.fixes[1].lat_deg, 43.2);
  EXPECT_EQ(ins.fixes[1].depth_m, 11.0);

  const InsTable with_attitude =
      readInsCsv(file("ins_att.csv", "t,lat,lon,depth,roll,pitch,heading\n0,43,5,10,1.5,-2,350\n"));
  EXPECT_TRUE(with_attitude.has_attitude);
  EXPECT_EQ(with_attitude.fixes[0].roll_deg, 1.5);
  EXPECT_EQ(with_attitude.fixes[0].pitch_deg, -2.0);
  EXPECT_EQ(with_attitude.fixes[0].heading_deg, 350.0);
}

TEST_F(CsvTableTest, ToleratesCrlfByteOrderMarkBlanksAroundCellsAndTrailingBlankLines) {
  const auto frames = readFramesCsv(file("frames.csv",
                                         "\xEF\xBB\xBF"
                                         "file,t\r\n a.png , 1 \r\nb.png,2\r\n\r\n  \n"));
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].file, "a.png");
  EXPECT_EQ(frames[0].t, 1.0);
  EXPECT_EQ(frames[1].t, 2.0);
}

TEST_F(CsvTableTest, MissingFile) {
  const auto path = folder_ / "absent.csv";
  expectInputError([&] { readFramesCsv(path); }, path,
                   " file not found");
}

TEST_F(CsvTableTest, EmptyFile) {
  const auto path = file("frames.csv", "");
  expectInputError([&] { readFramesCsv(path); }, path,
                   "line 1: empty file; expected the header 'file,t'");
  const auto blank = file("blank.csv", "\n\n");
  expectInputError([&] { readFramesCsv(blank); }, blank,
                   "line 1: empty file; expected the header 'file,t'");
}

TEST_F(CsvTableTest, HeaderOnly) {
  const auto path = file("lines.csv", "line,t\n");
  expectInputError([&] { readLinesCsv(path); }, path,
                   "line 2: no data rows; expected at least one row after the header 'line,t'");
}

TEST_F(CsvTableTest, WrongHeader) {
  const auto path = file("frames.csv", "file,time\na.png,1\n");
  expectInputError([&] { readFramesCsv(path); }, path,
                   "line 1: expected the header 'file,t', got 'file,time'");
  const auto swapped = file("swapped.csv", "t,file\n1,a.png\n");
  expectInputError([&] { readFramesCsv(swapped); }, swapped,
                   "line 1: expected the header 'file,t', got 't,file'");
}

TEST_F(CsvTableTest, InsAttitudeIsAllOrNothing) {
  const auto partial = file("ins.csv", "t,lat,lon,depth,roll\n0,43,5,10,1\n");
  expectInputError([&] { readInsCsv(partial); }, partial,
                   "line 1: expected the header 't,lat,lon,depth' or "
                   "'t,lat,lon,depth,roll,pitch,heading', got 't,lat,lon,depth,roll'");
  const auto short_row =
      file("ins2.csv", "t,lat,lon,depth,roll,pitch,heading\n0,43,5,10,1,2,3\n1,43,5,10,1,2\n");
  expectInputError([&] { readInsCsv(short_row); }, short_row,
                   "line 3: expected 7 columns (t,lat,lon,depth,roll,pitch,heading), got 6");
  const auto empty_cell = file("ins3.csv", "t,lat,lon,depth,roll,pitch,heading\n0,43,5,10,1,,3\n");
  expectInputError([&] { readInsCsv(empty_cell); }, empty_cell,
                   "line 2: column 'pitch': expected a number, got ''");
}

TEST_F(CsvTableTest, WrongColumnCount) {
  const auto path = file("frames.csv", "file,t\na.png,1\nb.png,2,3\n");
  expectInputError([&] { readFramesCsv(path); }, path,
                   "line 3: expected 2 columns (file,t), got 3");
  const auto one = file("one.csv", "file,t\na.png\n");
  expectInputError([&] { readFramesCsv(one); }, one, "line 2: expected 2 columns (file,t), got 1");
}

TEST_F(CsvTableTest, BlankLineInsideTable) {
  const auto path = file("frames.csv", "file,t\na.png,1\n\nb.png,2\n");
  expectInputError([&] { readFramesCsv(path); }, path,
                   "line 3: blank line inside the table; expected a row 'file,t'");
}

TEST_F(CsvTableTest, BadNumbers) {
  const auto text = file("frames.csv", "file,t\na.png,1\nb.png,x\n");
  expectInputError([&] { readFramesCsv(text); }, text,
                   "line 3: column 't': expected a number, got 'x'");
  const auto nan = file("ins.csv", "t,lat,lon,depth\n0,43,5,10\n1,nan,5,10\n");
  expectInputError([&] { readInsCsv(nan); }, nan,
                   "line 3: column 'lat': expected a finite number, got 'nan'");
  const auto inf = file("ins2.csv", "t,lat,lon,depth\n0,43,5,inf\n");
  expectInputError([&] { readInsCsv(inf); }, inf,
                   "line 2: column 'depth': expected a finite number, got 'inf'");
}

TEST_F(CsvTableTest, EmptyFileName) {
  const auto path = file("frames.csv", "file,t\n ,1\n");
  expectInputError([&] { readFramesCsv(path); }, path,
                   "line 2: column 'file': expected an image file name, got an empty cell");
}

TEST_F(CsvTableTest, UnsortedTimeStamps) {
  const auto path = file("frames.csv", "file,t\na.png,1\nb.png,2\nc.png,0.5\n");
  expectInputError(
      [&] { readFramesCsv(path); }, path,
      "line 4: time 't' = 0.5 is earlier than the previous row's 2: rows must be in time order");
  const auto ins =
      file("ins.csv", "t,lat,lon,depth\n1700000000.25,43,5,10\n1700000000.125,43,5,10\n");
  expectInputError([&] { readInsCsv(ins); }, ins,
                   "line 3: time 't' = 1700000000.125 is earlier than the previous row's "
                   "1700000000.25: rows must be in time order");
}

TEST_F(CsvTableTest, DuplicatedTimeStamps) {
  const auto path = file("lines.csv", "line,t\n0,1\n1,1.5\n2,1.5\n");
  expectInputError([&] { readLinesCsv(path); }, path,
                   "line 4: time 't' = 1.5 equals the previous row's: duplicated time stamp");
}

TEST_F(CsvTableTest, ScanLineIndicesCountFromZeroInOrder) {
  const auto gap = file("lines.csv", "line,t\n0,1\n2,2\n");
  expectInputError([&] { readLinesCsv(gap); }, gap,
                   "line 3: column 'line': expected scan line 1 (one row per scan line, counting "
                   "from 0 in order), got 2");
  const auto start = file("lines1.csv", "line,t\n1,1\n");
  expectInputError([&] { readLinesCsv(start); }, start,
                   "line 2: column 'line': expected scan line 0 (one row per scan line, counting "
                   "from 0 in order), got 1");
  const auto fraction = file("lines2.csv", "line,t\n0.5,1\n");
  expectInputError([&] { readLinesCsv(fraction); }, fraction,
                   "line 2: column 'line': expected an integer, got '0.5'");
}

TEST_F(CsvTableTest, InsValueRanges) {
  const auto lat = file("ins.csv", "t,lat,lon,depth\n0,95,5,10\n");
  expectInputError([&] { readInsCsv(lat); }, lat,
                   "line 2: column 'lat': expected a latitude in [-90, 90] degrees, got 95");
  const auto lon = file("ins2.csv", "t,lat,lon,depth\n0,43,-181,10\n");
  expectInputError([&] { readInsCsv(lon); }, lon,
                   "line 2: column 'lon': expected a longitude in [-180, 180] degrees, got -181");
  const auto pitch = file("ins3.csv", "t,lat,lon,depth,roll,pitch,heading\n0,43,5,10,0,91,0\n");
  expectInputError([&] { readInsCsv(pitch); }, pitch,
                   "line 2: column 'pitch': expected a pitch in [-90, 90] degrees, got 91");
}

TEST_F(CsvTableTest, WritersRoundTripExactly) {
  const std::vector<FrameRow> frames = {{"frame_0000.png", 1700000000.123456789, 0},
                                        {"frame_0001.png", 1700000000.163456789, 0},
                                        {"sub/frame 2.png", 1700000000.2 + 1e-9, 0}};
  writeFramesCsv(folder_ / "frames.csv", frames);
  const auto frames_back = readFramesCsv(folder_ / "frames.csv");
  ASSERT_EQ(frames_back.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames_back[i].file, frames[i].file);
    EXPECT_EQ(frames_back[i].t, frames[i].t);
    EXPECT_EQ(frames_back[i].line_number, static_cast<long long>(i) + 2);
  }

  const std::vector<double> lines = {12345.000001, 12345.033334333, 12345.0666677};
  writeLinesCsv(folder_ / "lines.csv", lines);
  EXPECT_EQ(readLinesCsv(folder_ / "lines.csv"), lines);
  EXPECT_EQ(testing::readText(folder_ / "lines.csv"),
            "line,t\n0,12345.000001\n1,12345.033334333\n2,12345.0666677\n");

  for (bool attitude : {false, true}) {
    InsTable ins;
    ins.has_attitude = attitude;
    ins.fixes.push_back({100.0, 43.123456789012, 5.000000001, 20.25, attitude ? 0.1 : 0.0,
                         attitude ? -0.2 : 0.0, attitude ? 359.9 : 0.0});
    ins.fixes.push_back({100.005, -43.5, -179.25, -1.5, 0.0, 0.0, 0.0});
    writeInsCsv(folder_ / "ins.csv", ins);
    const InsTable back = readInsCsv(folder_ / "ins.csv");
    EXPECT_EQ(back.has_attitude, attitude);
    ASSERT_EQ(back.fixes.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(back.fixes[i].t, ins.fixes[i].t);
      EXPECT_EQ(back.fixes[i].lat_deg, ins.fixes[i].lat_deg);
      EXPECT_EQ(back.fixes[i].lon_deg, ins.fixes[i].lon_deg);
      EXPECT_EQ(back.fixes[i].depth_m, ins.fixes[i].depth_m);
      EXPECT_EQ(back.fixes[i].roll_deg, ins.fixes[i].roll_deg);
      EXPECT_EQ(back.fixes[i].pitch_deg, ins.fixes[i].pitch_deg);
      EXPECT_EQ(back.fixes[i].heading_deg, ins.fixes[i].heading_deg);
    }
  }
  EXPECT_FALSE(std::filesystem::exists(folder_ / "ins.csv.partial"));
}

TEST_F(CsvTableTest, FramesWriterRefusesUnwritableNames) {
  EXPECT_THROW(writeFramesCsv(folder_ / "f.csv", {{"a,b.png", 1.0, 0}}), std::invalid_argument);
  EXPECT_THROW(writeFramesCsv(folder_ / "f.csv", {{"", 1.0, 0}}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(folder_ / "f.csv"));
}

}  // namespace
}  // namespace hsmap
