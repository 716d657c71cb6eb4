#include "core/survey/run_record.h"

#include <cctype>
#include <ctime>
#include <stdexcept>

#include "core/io/atomic_file.h"
#include "core/survey/calibration_yaml.h"
#include "core/survey/results_yaml.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"

namespace hsmap {
namespace {

// "YYYY-MM-DDTHH:MM:SSZ" with plausible field ranges; a full calendar check
// would add nothing a reader of the record needs.
bool isUtcTimestamp(const std::string& text) {
  const std::string pattern = "dddd-dd-ddTdd:dd:ddZ";
  if (text.size() != pattern.size()) return false;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    const bool digit = std::isdigit(static_cast<unsigned char>(text[i])) != 0;
    if (pattern[i] == 'd' ? !digit : text[i] != pattern[i]) return false;
  }
  const auto field = [&](std::size_t at) { return std::stoi(text.substr(at, 2)); };
  return field(5) >= 1 && field(5) <= 12 && field(8) >= 1 && field(8) <= 31 && field(11) <= 23 &&
         field(14) <= 59 && field(17) <= 60;  // 60: a leap second
}

std::map<std::string, std::string> readOptions(const StrictYamlMap& root,
                                               const YAML::Node& value) {
  const std::string key = "options";
  if (!root.has(key)) root.fail(key, "missing required key");
  if (!value.IsMap()) {
    root.fail(key, "expected a map of option names to texts (possibly empty: {}), got " +
                       describeYamlNode(value));
  }
  std::map<std::string, std::string> options;
  std::map<std::string, long long> first_line;
  for (auto it = value.begin(); it != value.end(); ++it) {
    const YAML::Mark mark = it->first.Mark();
    const long long line = mark.is_null() ? root.lineOf(key) : mark.line + 1;
    const std::string where_map = InputError::atLine(line) + ", " + InputError::atKey(key);
    if (!it->first.IsScalar() || it->first.Scalar().empty()) {
      throw InputError(root.file(), where_map,
                       "expected an option name, got " + describeYamlNode(it->first));
    }
    const std::string name = it->first.Scalar();
    requirePrintableText(root.file(), where_map, name);
    const std::string where = InputError::atLine(line) + ", " + InputError::atKey(key + "." + name);
    if (const auto first = first_line.find(name); first != first_line.end()) {
      throw InputError(root.file(), where,
                       "duplicated key (first given at line " + std::to_string(first->second) +
                           ")");
    }
    // A plain `key:` is null, not an empty text: an empty value is written "".
    if (!it->second.IsScalar()) {
      throw InputError(root.file(), where,
                       "expected a text value (\"\" for an empty one), got " +
                           describeYamlNode(it->second));
    }
    requirePrintableText(root.file(), where, it->second.Scalar());
    first_line[name] = line;
    options[name] = it->second.Scalar();
  }
  return options;
}

std::vector<StageRecord> readStages(const StrictYamlMap& root, const YAML::Node& value) {
  const std::string key = "stages";
  if (!root.has(key)) root.fail(key, "missing required key");
  if (!value.IsSequence()) {
    root.fail(key, "expected a list of {name, time_s, peak_rss_mb} maps (possibly empty: []), "
                   "got " + describeYamlNode(value));
  }
  std::vector<StageRecord> stages;
  std::map<std::string, long long> first_line;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const YAML::Node element = value[i];
    const YAML::Mark mark = element.Mark();
    const long long line = mark.is_null() ? root.lineOf(key) : mark.line + 1;
    const StrictYamlMap stage(root.file(), element, key + "[" + std::to_string(i) + "]", line,
                              {"name", "time_s", "peak_rss_mb"});
    StageRecord record;
    record.name = stage.text("name");
    if (record.name == "total") {
      stage.fail("name", "'total' is reserved (metrics.json's timings_s uses it for the whole "
                         "run); expected another stage name");
    }
    if (const auto first = first_line.find(record.name); first != first_line.end()) {
      stage.fail("name", "duplicated stage " + quoteForMessage(record.name) + " (first at line " +
                             std::to_string(first->second) + ")");
    }
    first_line[record.name] = stage.lineOf("name");
    record.time_s = readNonNegativeNumber(stage, "time_s");
    record.peak_rss_mb = readNonNegativeNumber(stage, "peak_rss_mb");
    stages.push_back(record);
  }
  return stages;
}

RunRecord parseDocument(const std::filesystem::path& file, const YAML::Node& document) {
  if (document.IsNull()) {
    throw InputError(file, InputError::atLine(1),
                     std::string("empty file; expected a YAML map starting with 'format: ") +
                         RunRecord::kFormat + "'");
  }
  const StrictYamlMap root(file, document, "", 1,
                           {"format", "program", "variant", "survey", "started_utc", "options",
                            "stages", "total_time_s", "peak_rss_mb"});
  const std::string format = root.text("format");
  if (format != RunRecord::kFormat) {
    root.fail("format", "unsupported format " + quoteForMessage(format) + "; expected '" +
                            RunRecord::kFormat + "'");
  }
  RunRecord record;
  const StrictYamlMap program = root.map("program", {"name", "version"});
  record.program_name = program.text("name");
  record.program_version = program.text("version");
  record.variant = readRunVariant(root, "variant");
  record.survey = root.text("survey");
  if (!record.survey.is_absolute()) {
    root.fail("survey", "expected the survey folder as an absolute path, got " +
                            quoteForMessage(record.survey.string()));
  }
  record.started_utc = root.text("started_utc");
  if (!isUtcTimestamp(record.started_utc)) {
    root.fail("started_utc", "expected a UTC time \"YYYY-MM-DDTHH:MM:SSZ\", got " +
                                 quoteForMessage(record.started_utc));
  }
  record.options = readOptions(root, document["options"]);
  record.stages = readStages(root, document["stages"]);
  record.total_time_s = readNonNegativeNumber(root, "total_time_s");
  record.peak_rss_mb = readNonNegativeNumber(root, "peak_rss_mb");
  return record;
}

std::string emitDocument(const RunRecord& record) {
  YAML::Emitter out;
  out << YAML::Comment("hsmap run record (format: see docs/EVALUATE.md)");
  out << YAML::BeginMap;
  out << YAML::Key << "format" << YAML::Value << RunRecord::kFormat;
  out << YAML::Key << "program" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << record.program_name;
  // Quoted: a version such as 1.10 must stay a text, not become the number 1.1.
  out << YAML::Key << "version" << YAML::Value << YAML::DoubleQuoted << record.program_version;
  out << YAML::EndMap;
  out << YAML::Key << "variant" << YAML::Value << record.variant;
  out << YAML::Key << "survey" << YAML::Value << record.survey.string();
  out << YAML::Key << "started_utc" << YAML::Value << YAML::DoubleQuoted << record.started_utc;
  out << YAML::Key << "options" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const auto& [name, value] : record.options) {
    out << YAML::Key << name << YAML::Value;
    if (value.empty()) {
      out << YAML::DoubleQuoted << value;
    } else {
      out << value;
    }
  }
  out << YAML::EndMap;
  out << YAML::Key << "stages" << YAML::Value;
  if (record.stages.empty()) out << YAML::Flow;  // `stages: []`
  out << YAML::BeginSeq;
  for (const StageRecord& stage : record.stages) {
    out << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "name" << YAML::Value << stage.name;
    out << YAML::Key << "time_s" << YAML::Value;
    emitNumber(out, stage.time_s);
    out << YAML::Key << "peak_rss_mb" << YAML::Value;
    emitNumber(out, stage.peak_rss_mb);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "total_time_s" << YAML::Value;
  emitNumber(out, record.total_time_s);
  out << YAML::Key << "peak_rss_mb" << YAML::Value;
  emitNumber(out, record.peak_rss_mb);
  out << YAML::EndMap;
  if (!out.good()) throw std::logic_error("writeRunRecord: YAML emitter: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

}  // namespace

RunRecord parseRunRecord(std::string_view text, const std::filesystem::path& file) {
  return parseDocument(file, parseYamlText(text, file));
}

RunRecord readRunRecord(const std::filesystem::path& file) {
  return parseDocument(file, loadYamlFile(file));
}

void writeRunRecord(const std::filesystem::path& file, const RunRecord& record) {
  const std::string text = emitDocument(record);
  try {
    parseRunRecord(text, file);
  } catch (const InputError& e) {
    throw std::invalid_argument(std::string("writeRunRecord: invalid run record: ") + e.what());
  }
  AtomicFile out(file);
  out.stream() << text;
  out.commit();
}

std::string formatUtcTimestamp(std::chrono::system_clock::time_point time) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(time);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace hsmap
