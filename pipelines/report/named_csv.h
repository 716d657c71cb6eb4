#pragma once
// NamedCsv: a CSV table of the run folder read by column name. The report
// reads files that several stages write and that may gain columns over time
// (frontend/keyframes.csv, georef/rejected_fixes.csv, report/ortho_patches.csv,
// ...): it asks for the columns it shows, and a file with more columns still
// reads, while a file without one of them, a row with the wrong number of
// cells or a cell that is not a number is an InputError naming the file, the
// 1-based line and the column, e.g.
//   "RUN/frontend/keyframes.csv:line 4: column 'x': expected a number, got 'abc'".
// No quoting (no hsmap table needs a comma in a cell); blank lines are skipped.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace hsmap {

class NamedCsv {
 public:
  // Reads `file`; every name of `required_columns` must be in its header.
  NamedCsv(const std::filesystem::path& file, const std::vector<std::string>& required_columns);
  // The same on the file's content `text`; `file` names it in errors.
  NamedCsv(std::string_view text, const std::filesystem::path& file,
           const std::vector<std::string>& required_columns);

  std::size_t rowCount() const { return rows_.size(); }
  bool hasColumn(std::string_view column) const;
  // Cell of `column` (one of the header's names) in data row `row`.
  const std::string& text(std::size_t row, std::string_view column) const;
  double number(std::size_t row, std::string_view column) const;
  long long integer(std::size_t row, std::string_view column) const;
  long long lineNumber(std::size_t row) const { return rows_[row].line_number; }
  const std::filesystem::path& file() const { return file_; }

 private:
  struct Row {
    long long line_number = 0;
    std::vector<std::string> cells;
  };
  std::size_t columnIndex(std::string_view column) const;
  void parse(std::string_view text, const std::vector<std::string>& required_columns);

  std::filesystem::path file_;
  std::vector<std::string> columns_;
  std::vector<Row> rows_;
};

}  // namespace hsmap
