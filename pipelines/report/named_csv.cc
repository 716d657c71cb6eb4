#include "pipelines/report/named_csv.h"

#include <algorithm>
#include <stdexcept>

#include "core/survey/number_text.h"
#include "core/util/input_error.h"
#include "core/util/text_file.h"

namespace hsmap {

namespace {

std::vector<std::string> splitCells(std::string_view line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view cell = line.substr(start, comma == std::string_view::npos ? line.npos : comma - start);
    cells.emplace_back(trimBlanks(cell));
    if (comma == std::string_view::npos) return cells;
    start = comma + 1;
  }
}

}  // namespace

NamedCsv::NamedCsv(const std::filesystem::path& file, const std::vector<std::string>& required_columns)
    : file_(file) {
  parse(normaliseText(readTextFile(file, kMaxCsvBytes), file, TextEncoding::utf8), required_columns);
}

NamedCsv::NamedCsv(std::string_view text, const std::filesystem::path& file,
                   const std::vector<std::string>& required_columns)
    : file_(file) {
  parse(normaliseText(text, file, TextEncoding::utf8), required_columns);
}

void NamedCsv::parse(std::string_view text, const std::vector<std::string>& required_columns) {
  long long line_number = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++line_number;
    if (trimBlanks(line).empty()) continue;
    std::vector<std::string> cells = splitCells(line);
    if (columns_.empty()) {
      columns_ = std::move(cells);
      continue;
    }
    if (cells.size() != columns_.size()) {
      throw InputError(file_, InputError::atLine(line_number),
                       "expected " + std::to_string(columns_.size()) + " comma-separated cells (as the header), got " +
                           std::to_string(cells.size()));
    }
    rows_.push_back({line_number, std::move(cells)});
  }
  if (columns_.empty()) throw InputError(file_, "", "is empty; expected a header line");
  for (const std::string& column : required_columns) {
    if (!hasColumn(column)) {
      std::string header;
      for (const std::string& name : columns_) header += (header.empty() ? "" : ",") + name;
      throw InputError(file_, InputError::atLine(1),
                       "expected a column '" + column + "' in the header, got '" + header + "'");
    }
  }
}

bool NamedCsv::hasColumn(std::string_view column) const {
  return std::find(columns_.begin(), columns_.end(), column) != columns_.end();
}

std::size_t NamedCsv::columnIndex(std::string_view column) const {
  const auto found = std::find(columns_.begin(), columns_.end(), column);
  if (found == columns_.end()) {
    throw std::logic_error("NamedCsv: " + file_.string() + " has no column '" + std::string(column) +
                           "' (ask for it in required_columns)");
  }
  return std::size_t(found - columns_.begin());
}

const std::string& NamedCsv::text(std::size_t row, std::string_view column) const {
  return rows_.at(row).cells[columnIndex(column)];
}

double NamedCsv::number(std::size_t row, std::string_view column) const {
  std::string message;
  const std::optional<double> value = parseFiniteDouble(text(row, column), &message);
  if (!value) {
    throw InputError(file_, InputError::atLine(rows_[row].line_number),
                     "column '" + std::string(column) + "': " + message);
  }
  return *value;
}

long long NamedCsv::integer(std::size_t row, std::string_view column) const {
  std::string message;
  const std::optional<long long> value = parseInteger(text(row, column), &message);
  if (!value) {
    throw InputError(file_, InputError::atLine(rows_[row].line_number),
                     "column '" + std::string(column) + "': " + message);
  }
  return *value;
}

}  // namespace hsmap
