#pragma once
// The survey's CSV tables (docs/SURVEY_FORMAT.md): rgb/frames.csv (file,t),
// uhi/lines.csv (line,t) and nav/ins.csv (t,lat,lon,depth[,roll,pitch,heading]),
// read strictly and written so that they read back identically.
//
// Contract of the reader (CsvTable):
//   - line 1 is the header and must equal one of the accepted headers exactly
//     (column names and order); ins.csv accepts its attitude columns only as a
//     complete trailing group, so attitude is all-or-nothing for a whole file;
//   - every data row has exactly as many comma-separated cells as the header;
//     there is no quoting (no survey column needs a comma); spaces and tabs
//     around a cell are ignored;
//   - the text checks of core/util/text_file.h come first: UTF-8 only, no
//     control characters (a NUL in a file name would silently cut it); CRLF
//     and CR-only line ends and a UTF-8 byte-order mark are tolerated, and so
//     are blank lines at the end of the file; a blank line followed by more data
//     is an error, because it usually means a damaged or concatenated file;
//   - a table without any data row is an error;
//   - numbers go through number_text.h: NaN and Inf are rejected; times
//     (column 't') must lie in [-4e9, 4e9] s (beyond, a float64 cannot hold
//     microseconds); depths in [-10000, 12000] m.
// Files are read as regular files of at most kMaxCsvBytes (text_file.h): a
// FIFO or a device is an error, never a hang.
// Errors are InputError naming the file and the 1-based line, e.g.
//   "nav/ins.csv:line 5: column 'lat': expected a finite number, got 'nan'".
//
// Time stamps (column 't') must be strictly increasing: a row earlier than
// the previous one, or equal to it, is an error (interpolation, spline knots
// and frame matching all rely on it).

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace hsmap {

// A parsed table: header names and the cells of each data row, with the
// 1-based text line each row came from (for error messages).
struct CsvTable {
  struct Row {
    long long line_number = 0;
    std::vector<std::string> cells;
  };
  std::filesystem::path file;
  std::vector<std::string> columns;
  std::vector<Row> rows;

  // Cell `column` of `row` as a finite double / an integer; throws InputError
  // "<file>:line N: column '<name>': expected a number, got '<text>'".
  double number(const Row& row, std::size_t column) const;
  long long integer(const Row& row, std::size_t column) const;
};

// Reads `file`, whose header must equal one of `accepted_headers` (each a list
// of column names in order). Throws InputError on any violation listed above.
CsvTable readCsvTable(const std::filesystem::path& file,
                      const std::vector<std::vector<std::string>>& accepted_headers);
// The same on the file's content `raw`; `file` names it in errors.
CsvTable parseCsvTable(std::string_view raw, const std::filesystem::path& file,
                       const std::vector<std::vector<std::string>>& accepted_headers);

// Checks that time `t` of `row` (column `column`) is later than the previous
// row's `previous_t`; throws InputError naming the row's line otherwise.
// Readers call it row by row, so the first error in file order is reported.
void checkTimeOrder(const CsvTable& table, const CsvTable::Row& row, std::size_t column,
                    double previous_t, double t);

// ---- rgb/frames.csv -------------------------------------------------------

struct FrameRow {
  std::string file;           // as written: relative to the folder holding frames.csv (or absolute)
  double t = 0.0;             // seconds, shared clock
  long long line_number = 0;  // 1-based line in frames.csv (0 when not read from a file)
};
std::vector<FrameRow> readFramesCsv(const std::filesystem::path& file);
std::vector<FrameRow> parseFramesCsv(std::string_view raw, const std::filesystem::path& file);
void writeFramesCsv(const std::filesystem::path& file, const std::vector<FrameRow>& frames);

// ---- uhi/lines.csv --------------------------------------------------------

// Recorded time of every scan line; element i is line i. The 'line' column
// must count 0, 1, 2, ... in order, so the row of scan line i is data row i.
std::vector<double> readLinesCsv(const std::filesystem::path& file);
std::vector<double> parseLinesCsv(std::string_view raw, const std::filesystem::path& file);
void writeLinesCsv(const std::filesystem::path& file, const std::vector<double>& line_times);

// ---- nav/ins.csv ----------------------------------------------------------

// One INS fix: the geodetic position of B (lat, lon on WGS-84, depth = -h) and,
// when the file has attitude, roll/pitch/heading in degrees (ZYX, body to NED).
// Ranges checked on reading: lat in [-90, 90], lon in [-180, 180],
// roll in [-180, 180], pitch in [-90, 90], heading in [-180, 360].
struct InsFix {
  double t = 0.0;
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double depth_m = 0.0;
  double roll_deg = 0.0;  // the three attitude angles are 0 when the file has none
  double pitch_deg = 0.0;
  double heading_deg = 0.0;
  long long line_number = 0;  // 1-based line in ins.csv (0 when not read from a file)
};
struct InsTable {
  bool has_attitude = false;
  std::vector<InsFix> fixes;
};
InsTable readInsCsv(const std::filesystem::path& file);
InsTable parseInsCsv(std::string_view raw, const std::filesystem::path& file);
// Writes the attitude columns iff `table.has_attitude`.
void writeInsCsv(const std::filesystem::path& file, const InsTable& table);

}  // namespace hsmap
