#include "pipelines/compare/compare_csv.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/survey/number_text.h"
#include "core/util/input_error.h"
#include "core/util/text_file.h"

namespace hsmap {

namespace {

constexpr std::size_t kLeadingColumns = 3;  // key, better, best

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void writeLine(std::ostringstream& out, const std::vector<std::string>& fields) {
  for (std::size_t i = 0; i < fields.size(); ++i) out << (i ? "," : "") << csvField(fields[i]);
  out << "\n";
}

std::string joined(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& word : words) text += (text.empty() ? "" : " ") + word;
  return text;
}

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> list;
  std::istringstream in(text);
  for (std::string word; in >> word;) list.push_back(word);
  return list;
}

// Records of RFC 4180 CSV with their first line numbers; a quoted field may
// hold line breaks.
struct CsvRecord {
  long long line = 0;
  std::vector<std::string> fields;
};

std::vector<CsvRecord> splitCsv(std::string_view text, const std::filesystem::path& file) {
  std::vector<CsvRecord> records;
  long long line = 1;
  std::size_t at = 0;
  while (at < text.size()) {
    CsvRecord record{line, {}};
    std::string field;
    bool quoted = false, field_started = false;
    for (; at < text.size(); ++at) {
      const char c = text[at];
      if (quoted) {
        if (c == '"' && at + 1 < text.size() && text[at + 1] == '"') {
          field += '"';
          ++at;
        } else if (c == '"') {
          quoted = false;
        } else {
          if (c == '\n') ++line;
          field += c;
        }
      } else if (c == '"' && !field_started) {
        quoted = field_started = true;
      } else if (c == ',') {
        record.fields.push_back(field);
        field.clear();
        field_started = false;
      } else if (c == '\n') {
        break;
      } else {
        field += c;
        field_started = true;
      }
    }
    if (quoted) throw InputError(file, InputError::atLine(record.line), "a quoted field that does not end");
    record.fields.push_back(field);
    records.push_back(std::move(record));
    ++at;  // the line's end
    ++line;
  }
  return records;
}

}  // namespace

std::string compareCsv(const CompareTable& table) {
  std::ostringstream out;
  std::vector<std::string> header = {"key", "better", "best"};
  for (const VariantOutcome& variant : table.variants) header.push_back(variant.variant);
  writeLine(out, header);
  auto text_row = [&](const std::string& key, auto field_of) {
    std::vector<std::string> fields = {key, "", ""};
    for (const VariantOutcome& variant : table.variants) fields.push_back(field_of(variant));
    writeLine(out, fields);
  };
  text_row("status", [](const VariantOutcome& v) { return v.status; });
  text_row("shared_stages", [](const VariantOutcome& v) { return joined(v.shared_stages); });
  text_row("shared_from", [](const VariantOutcome& v) { return v.shared_from; });
  for (const auto* rows : {&table.time_rows, &table.metric_rows}) {
    for (const CompareRow& row : *rows) {
      std::vector<std::string> fields = {row.key, toString(row.better), bestVariants(table, row)};
      for (const auto& value : row.values) fields.push_back(value ? formatDouble(*value) : "");
      writeLine(out, fields);
    }
  }
  return out.str();
}

void writeCompareCsv(const std::filesystem::path& file, const CompareTable& table) {
  AtomicFile out(file);
  out.stream() << compareCsv(table);
  out.commit();
}

CompareTable parseCompareCsv(std::string_view text, const std::filesystem::path& file) {
  const std::string normal = normaliseText(text, file, TextEncoding::utf8);
  const std::vector<CsvRecord> records = splitCsv(normal, file);
  if (records.empty() || records[0].fields.size() <= kLeadingColumns || records[0].fields[0] != "key" ||
      records[0].fields[1] != "better" || records[0].fields[2] != "best") {
    throw InputError(file, InputError::atLine(1), "expected the header key,better,best and one column per variant");
  }
  CompareTable table;
  for (std::size_t c = kLeadingColumns; c < records[0].fields.size(); ++c) {
    table.variants.push_back(VariantOutcome{});
    table.variants.back().variant = records[0].fields[c];
  }
  const std::size_t columns = records[0].fields.size();
  for (std::size_t r = 1; r < records.size(); ++r) {
    const CsvRecord& record = records[r];
    const std::string where = InputError::atLine(record.line);
    if (record.fields.size() == 1 && record.fields[0].empty() && r + 1 == records.size()) break;  // final newline
    if (record.fields.size() != columns) {
      throw InputError(file, where, "expected " + std::to_string(columns) + " fields, got " +
                                        std::to_string(record.fields.size()));
    }
    const std::string& key = record.fields[0];
    if (key == "status" || key == "shared_stages" || key == "shared_from") {
      for (std::size_t c = 0; c < table.variants.size(); ++c) {
        const std::string& field = record.fields[kLeadingColumns + c];
        VariantOutcome& variant = table.variants[c];
        if (key == "status") variant.status = field;
        if (key == "shared_stages") variant.shared_stages = words(field);
        if (key == "shared_from") variant.shared_from = field;
      }
      continue;
    }
    CompareRow row;
    row.key = key;
    try {
      row.better = parseBetter(record.fields[1]);
    } catch (const std::invalid_argument& failure) {
      throw InputError(file, where, "column 'better': " + std::string(failure.what()));
    }
    const std::vector<std::string> best = words(record.fields[2]);
    for (std::size_t c = 0; c < table.variants.size(); ++c) {
      const std::string& field = record.fields[kLeadingColumns + c];
      std::optional<double> value;
      if (!field.empty()) {
        std::string message;
        value = parseFiniteDouble(field, &message);
        if (!value) {
          throw InputError(file, where, "column '" + table.variants[c].variant + "': expected a number or "
                                        "nothing, got '" + field + "'");
        }
      }
      row.values.push_back(value);
      row.best.push_back(std::find(best.begin(), best.end(), table.variants[c].variant) != best.end());
      VariantOutcome& variant = table.variants[c];
      if (key == "wall_time_s") {
        variant.wall_time_s = value.value_or(0.0);
      } else if (key.starts_with("time_s.")) {
        if (value) variant.stages.push_back({key.substr(7), *value});
      } else {
        variant.metrics.emplace_back(key, value);
      }
    }
    (key == "wall_time_s" || key.starts_with("time_s.") ? table.time_rows : table.metric_rows)
        .push_back(std::move(row));
  }
  return table;
}

CompareTable readCompareCsv(const std::filesystem::path& file) {
  return parseCompareCsv(readTextFile(file, kMaxCsvBytes), file);
}

}  // namespace hsmap
