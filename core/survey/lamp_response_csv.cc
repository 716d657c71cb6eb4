#include "core/survey/lamp_response_csv.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/io/atomic_file.h"
#include "core/survey/csv_table.h"
#include "core/survey/number_text.h"
#include "core/util/input_error.h"
#include "core/util/text_file.h"

namespace hsmap {

std::vector<double> readLampResponseCsv(const std::filesystem::path& file) {
  return parseLampResponseCsv(readTextFile(file, kMaxCsvBytes), file);
}

std::vector<double> parseLampResponseCsv(std::string_view raw, const std::filesystem::path& file) {
  const CsvTable table = parseCsvTable(raw, file, {{"band", "dn"}});
  std::vector<double> dn;
  dn.reserve(table.rows.size());
  for (const auto& row : table.rows) {
    const long long expected = static_cast<long long>(dn.size());
    const long long band = table.integer(row, 0);
    if (band != expected) {
      throw InputError(file, InputError::atLine(row.line_number),
                       "column 'band': expected band " + std::to_string(expected) +
                           " (one row per UHI band, counting from 0 in order), got " +
                           std::to_string(band));
    }
    const double value = table.number(row, 1);
    if (!(value > 0.0)) {
      throw InputError(file, InputError::atLine(row.line_number),
                       "column 'dn': expected a DN > 0 (one lamp's response on a white target "
                       "at 1 m), got " + formatDouble(value));
    }
    dn.push_back(value);
  }
  return dn;
}

void writeLampResponseCsv(const std::filesystem::path& file, const std::vector<double>& dn) {
  if (dn.empty()) throw std::invalid_argument("writeLampResponseCsv: no band");
  std::string text = "band,dn\n";
  for (std::size_t b = 0; b < dn.size(); ++b) {
    if (!std::isfinite(dn[b]) || !(dn[b] > 0.0)) {
      throw std::invalid_argument("writeLampResponseCsv: band " + std::to_string(b) +
                                  ": expected a finite DN > 0, got " + formatDouble(dn[b]));
    }
    text += std::to_string(b) + ',' + formatDouble(dn[b]) + '\n';
  }
  AtomicFile out(file);
  out.stream() << text;
  out.commit();
}

}  // namespace hsmap
