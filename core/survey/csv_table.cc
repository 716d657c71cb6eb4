#include "core/survey/csv_table.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/survey/number_text.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"
#include "core/util/text_file.h"

namespace hsmap {
namespace {

std::string joinColumns(const std::vector<std::string>& columns) {
  std::string text;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i > 0) text += ',';
    text += columns[i];
  }
  return text;
}

std::vector<std::string> splitCells(std::string_view line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view cell = line.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    cells.emplace_back(trimBlanks(cell));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cells;
}


// Splits normalised text (LF line ends only) into lines.
std::vector<std::string_view> splitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

void writeAtomically(const std::filesystem::path& file, const std::string& text) {
  AtomicFile out(file);
  out.stream() << text;
  out.commit();
}

void requireFiniteForWriting(double value, const char* what) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(std::string("CSV writer: non-finite ") + what);
  }
}

// Times are seconds on the survey's shared clock (UNIX or GPS seconds, or
// seconds since the dive started). Beyond 4e9 s a float64 no longer resolves
// a microsecond, so a larger value is damage, not a time (1e300 would pass
// every other check).
constexpr double kMaxAbsTimeS = 4e9;

double timeCell(const CsvTable& table, const CsvTable::Row& row, std::size_t column) {
  const double t = table.number(row, column);
  if (std::abs(t) > kMaxAbsTimeS) {
    throw InputError(table.file, InputError::atLine(row.line_number),
                     "column '" + table.columns[column] + "': expected a time in [-4e9, 4e9] s, got " +
                         formatDouble(t) +
                         " (seconds on the survey's clock; a float64 beyond 4e9 s cannot hold "
                         "microseconds)");
  }
  return t;
}

// Depth d is the height h = -d on WGS-84: from above the highest lake
// (h ~ 5,000 m) to below the deepest trench (~11,000 m), with margin.
constexpr double kMinDepthM = -10000.0;
constexpr double kMaxDepthM = 12000.0;

void checkRange(const CsvTable& table, const CsvTable::Row& row, std::size_t column, double value,
                double low, double high, const char* what) {
  if (value < low || value > high) {
    throw InputError(table.file, InputError::atLine(row.line_number),
                     "column '" + table.columns[column] + "': expected " + what + " in [" +
                         formatDouble(low) + ", " + formatDouble(high) + "] degrees, got " +
                         formatDouble(value));
  }
}

}  // namespace

double CsvTable::number(const Row& row, std::size_t column) const {
  std::string message;
  const auto value = parseFiniteDouble(row.cells.at(column), &message);
  if (!value) {
    throw InputError(file, InputError::atLine(row.line_number),
                     "column '" + columns.at(column) + "': " + message);
  }
  return *value;
}

long long CsvTable::integer(const Row& row, std::size_t column) const {
  std::string message;
  const auto value = parseInteger(row.cells.at(column), &message);
  if (!value) {
    throw InputError(file, InputError::atLine(row.line_number),
                     "column '" + columns.at(column) + "': " + message);
  }
  return *value;
}

CsvTable readCsvTable(const std::filesystem::path& file,
                      const std::vector<std::vector<std::string>>& accepted_headers) {
  return parseCsvTable(readTextFile(file, kMaxCsvBytes), file, accepted_headers);
}

CsvTable parseCsvTable(std::string_view raw, const std::filesystem::path& file,
                       const std::vector<std::vector<std::string>>& accepted_headers) {
  if (accepted_headers.empty()) throw std::invalid_argument("readCsvTable: no accepted header");
  std::string expected_headers;
  for (std::size_t i = 0; i < accepted_headers.size(); ++i) {
    if (i > 0) expected_headers += " or ";
    expected_headers += '\'';
    expected_headers += joinColumns(accepted_headers[i]);
    expected_headers += '\'';
  }

  // UTF-8 checked, control characters refused, byte-order mark and CR / CRLF
  // line ends normalised (text_file.h).
  const std::string text = normaliseText(raw, file, TextEncoding::utf8);
  std::vector<std::string_view> lines = splitLines(text);
  // Blank lines at the end are harmless (editors add them); drop them.
  while (!lines.empty() && trimBlanks(lines.back()).empty()) lines.pop_back();
  if (lines.empty()) {
    throw InputError(file, InputError::atLine(1),
                     "empty file; expected the header " + expected_headers);
  }

  CsvTable table;
  table.file = file;
  table.columns = splitCells(lines[0]);
  bool header_ok = false;
  for (const auto& accepted : accepted_headers) header_ok = header_ok || table.columns == accepted;
  if (!header_ok) {
    throw InputError(
        file, InputError::atLine(1),
        "expected the header " + expected_headers + ", got " + quoteForMessage(lines[0]));
  }
  if (lines.size() == 1) {
    throw InputError(file, InputError::atLine(2),
                     "no data rows; expected at least one row after the header '" +
                         joinColumns(table.columns) + "'");
  }

  table.rows.reserve(lines.size() - 1);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const long long line_number = static_cast<long long>(i) + 1;
    if (trimBlanks(lines[i]).empty()) {
      throw InputError(
          file, InputError::atLine(line_number),
          "blank line inside the table; expected a row '" + joinColumns(table.columns) + "'");
    }
    CsvTable::Row row{line_number, splitCells(lines[i])};
    if (row.cells.size() != table.columns.size()) {
      throw InputError(file, InputError::atLine(line_number),
                       "expected " + std::to_string(table.columns.size()) + " columns (" +
                           joinColumns(table.columns) + "), got " +
                           std::to_string(row.cells.size()));
    }
    table.rows.push_back(std::move(row));
  }
  return table;
}

void checkTimeOrder(const CsvTable& table, const CsvTable::Row& row, std::size_t column,
                    double previous_t, double t) {
  if (t > previous_t) return;
  const std::string& name = table.columns.at(column);
  if (t == previous_t) {
    throw InputError(table.file, InputError::atLine(row.line_number),
                     "time '" + name + "' = " + formatDouble(t) +
                         " equals the previous row's: duplicated time stamp");
  }
  throw InputError(table.file, InputError::atLine(row.line_number),
                   "time '" + name + "' = " + formatDouble(t) +
                       " is earlier than the previous row's " + formatDouble(previous_t) +
                       ": rows must be in time order");
}

// ---- rgb/frames.csv -------------------------------------------------------

std::vector<FrameRow> readFramesCsv(const std::filesystem::path& file) {
  return parseFramesCsv(readTextFile(file, kMaxCsvBytes), file);
}

std::vector<FrameRow> parseFramesCsv(std::string_view raw, const std::filesystem::path& file) {
  const CsvTable table = parseCsvTable(raw, file, {{"file", "t"}});
  std::vector<FrameRow> frames;
  frames.reserve(table.rows.size());
  for (const auto& row : table.rows) {
    if (row.cells[0].empty()) {
      throw InputError(file, InputError::atLine(row.line_number),
                       "column 'file': expected an image file name, got an empty cell");
    }
    const double t = timeCell(table, row, 1);
    if (!frames.empty()) checkTimeOrder(table, row, 1, frames.back().t, t);
    frames.push_back({row.cells[0], t, row.line_number});
  }
  return frames;
}

void writeFramesCsv(const std::filesystem::path& file, const std::vector<FrameRow>& frames) {
  std::string text = "file,t\n";
  for (const auto& frame : frames) {
    if (frame.file.empty() || frame.file.find_first_of(",\r\n") != std::string::npos ||
        trimBlanks(frame.file) != frame.file) {
      throw std::invalid_argument("writeFramesCsv: file name '" + frame.file +
                                  "' cannot be written to a CSV cell without quoting");
    }
    requireFiniteForWriting(frame.t, "frame time");
    text += frame.file + ',' + formatDouble(frame.t) + '\n';
  }
  writeAtomically(file, text);
}

// ---- uhi/lines.csv --------------------------------------------------------

std::vector<double> readLinesCsv(const std::filesystem::path& file) {
  return parseLinesCsv(readTextFile(file, kMaxCsvBytes), file);
}

std::vector<double> parseLinesCsv(std::string_view raw, const std::filesystem::path& file) {
  const CsvTable table = parseCsvTable(raw, file, {{"line", "t"}});
  std::vector<double> times;
  times.reserve(table.rows.size());
  for (const auto& row : table.rows) {
    const long long expected = static_cast<long long>(times.size());
    const long long line = table.integer(row, 0);
    if (line != expected) {
      throw InputError(file, InputError::atLine(row.line_number),
                       "column 'line': expected scan line " + std::to_string(expected) +
                           " (one row per scan line, counting from 0 in order), got " +
                           std::to_string(line));
    }
    const double t = timeCell(table, row, 1);
    if (!times.empty()) checkTimeOrder(table, row, 1, times.back(), t);
    times.push_back(t);
  }
  return times;
}

void writeLinesCsv(const std::filesystem::path& file, const std::vector<double>& line_times) {
  std::string text = "line,t\n";
  for (std::size_t i = 0; i < line_times.size(); ++i) {
    requireFiniteForWriting(line_times[i], "scan line time");
    text += std::to_string(i) + ',' + formatDouble(line_times[i]) + '\n';
  }
  writeAtomically(file, text);
}

// ---- nav/ins.csv ----------------------------------------------------------

InsTable readInsCsv(const std::filesystem::path& file) {
  return parseInsCsv(readTextFile(file, kMaxCsvBytes), file);
}

InsTable parseInsCsv(std::string_view raw, const std::filesystem::path& file) {
  const CsvTable table = parseCsvTable(
      raw, file,
      {{"t", "lat", "lon", "depth"}, {"t", "lat", "lon", "depth", "roll", "pitch", "heading"}});
  InsTable ins;
  ins.has_attitude = table.columns.size() == 7;
  ins.fixes.reserve(table.rows.size());
  for (const auto& row : table.rows) {
    InsFix fix;
    fix.t = timeCell(table, row, 0);
    fix.line_number = row.line_number;
    if (!ins.fixes.empty()) checkTimeOrder(table, row, 0, ins.fixes.back().t, fix.t);
    fix.lat_deg = table.number(row, 1);
    checkRange(table, row, 1, fix.lat_deg, -90.0, 90.0, "a latitude");
    fix.lon_deg = table.number(row, 2);
    checkRange(table, row, 2, fix.lon_deg, -180.0, 180.0, "a longitude");
    fix.depth_m = table.number(row, 3);
    if (fix.depth_m < kMinDepthM || fix.depth_m > kMaxDepthM) {
      throw InputError(file, InputError::atLine(row.line_number),
                       "column 'depth': expected a depth in [-10000, 12000] m, got " +
                           formatDouble(fix.depth_m));
    }
    if (ins.has_attitude) {
      fix.roll_deg = table.number(row, 4);
      checkRange(table, row, 4, fix.roll_deg, -180.0, 180.0, "a roll");
      fix.pitch_deg = table.number(row, 5);
      checkRange(table, row, 5, fix.pitch_deg, -90.0, 90.0, "a pitch");
      fix.heading_deg = table.number(row, 6);
      checkRange(table, row, 6, fix.heading_deg, -180.0, 360.0, "a heading");
    }
    ins.fixes.push_back(fix);
  }
  return ins;
}

void writeInsCsv(const std::filesystem::path& file, const InsTable& table) {
  std::string text =
      table.has_attitude ? "t,lat,lon,depth,roll,pitch,heading\n" : "t,lat,lon,depth\n";
  for (const auto& fix : table.fixes) {
    const double values[] = {fix.t,        fix.lat_deg,   fix.lon_deg,    fix.depth_m,
                             fix.roll_deg, fix.pitch_deg, fix.heading_deg};
    const std::size_t count = table.has_attitude ? 7 : 4;
    for (std::size_t i = 0; i < count; ++i) {
      requireFiniteForWriting(values[i], "INS value");
      if (i > 0) text += ',';
      text += formatDouble(values[i]);
    }
    text += '\n';
  }
  writeAtomically(file, text);
}

}  // namespace hsmap
