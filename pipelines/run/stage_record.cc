#include "pipelines/run/stage_record.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/io/atomic_file.h"
#include "core/survey/number_text.h"

namespace hsmap {

namespace fs = std::filesystem;

fs::path stageRecordPath(const fs::path& run, const std::string& stage) {
  return run / "stages" / (stage + ".yaml");
}

void writeStageRecord(const fs::path& file, const StageRecordFile& record) {
  YAML::Emitter yaml;
  yaml << YAML::BeginMap;
  yaml << YAML::Key << "format" << YAML::Value << StageRecordFile::kFormat;
  yaml << YAML::Key << "stage" << YAML::Value << record.stage;
  yaml << YAML::Key << "variant" << YAML::Value << record.variant;
  yaml << YAML::Key << "survey" << YAML::Value << YAML::DoubleQuoted << record.survey;
  yaml << YAML::Key << "fingerprint" << YAML::Value << YAML::DoubleQuoted << record.fingerprint;
  yaml << YAML::Key << "options" << YAML::Value << YAML::Literal << record.options;
  yaml << YAML::Key << "time_s" << YAML::Value << formatDouble(record.time_s);
  yaml << YAML::Key << "peak_rss_mb" << YAML::Value << formatDouble(record.peak_rss_mb);
  yaml << YAML::Key << "outputs" << YAML::Value << YAML::BeginSeq;
  for (const StageOutputFile& output : record.outputs) {
    yaml << YAML::Flow << YAML::BeginMap << YAML::Key << "path" << YAML::Value << YAML::DoubleQuoted
         << output.path << YAML::Key << "bytes" << YAML::Value << output.bytes << YAML::EndMap;
  }
  yaml << YAML::EndSeq << YAML::EndMap;
  fs::create_directories(file.parent_path());
  AtomicFile out(file);
  out.stream() << yaml.c_str() << "\n";
  out.commit();
}

std::optional<StageRecordFile> readStageRecord(const fs::path& file, std::string& why) {
  std::error_code error;
  if (!fs::is_regular_file(file, error)) {
    why = "no record " + file.string();
    return std::nullopt;
  }
  try {
    const YAML::Node node = YAML::LoadFile(file.string());
    if (node["format"].as<std::string>() != StageRecordFile::kFormat) {
      why = file.string() + ": format is not " + StageRecordFile::kFormat;
      return std::nullopt;
    }
    StageRecordFile record;
    record.stage = node["stage"].as<std::string>();
    record.variant = node["variant"].as<std::string>();
    record.survey = node["survey"].as<std::string>();
    record.fingerprint = node["fingerprint"].as<std::string>();
    record.options = node["options"].as<std::string>();
    record.time_s = node["time_s"].as<double>();
    record.peak_rss_mb = node["peak_rss_mb"].as<double>();
    for (const YAML::Node& output : node["outputs"]) {
      record.outputs.push_back({output["path"].as<std::string>(), output["bytes"].as<std::uintmax_t>()});
    }
    return record;
  } catch (const YAML::Exception& failure) {
    why = file.string() + ": unreadable (" + failure.what() + ")";
    return std::nullopt;
  }
}

std::vector<StageOutputFile> listStageOutputs(const fs::path& run, const std::vector<fs::path>& outputs) {
  std::vector<StageOutputFile> files;
  auto add = [&](const fs::path& path) {
    files.push_back({path.lexically_relative(run).generic_string(), fs::file_size(path)});
  };
  for (const fs::path& output : outputs) {
    const fs::path path = run / output;
    std::error_code error;
    if (fs::is_regular_file(path, error)) {
      add(path);
    } else if (fs::is_directory(path, error)) {
      for (const auto& entry : fs::recursive_directory_iterator(path)) {
        if (entry.is_regular_file()) add(entry.path());
      }
    }
  }
  std::sort(files.begin(), files.end(),
            [](const StageOutputFile& a, const StageOutputFile& b) { return a.path < b.path; });
  return files;
}

std::string surveyStamp(const fs::path& survey, const fs::path& run) {
  std::vector<std::string> lines;
  const fs::path root = fs::absolute(survey).lexically_normal();
  const fs::path run_folder = fs::absolute(run).lexically_normal();
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    const fs::path relative = it->path().lexically_relative(root);
    if (it->is_directory() && (relative == "truth" || it->path().lexically_normal() == run_folder)) {
      it.disable_recursion_pending();  // the truth is not an input
      continue;
    }
    if (!it->is_regular_file()) continue;
    const auto modified = fs::last_write_time(it->path()).time_since_epoch().count();
    lines.push_back(relative.generic_string() + " " + std::to_string(it->file_size()) + " " +
                    std::to_string(modified));
  }
  std::sort(lines.begin(), lines.end());
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

std::string fingerprintOf(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

}  // namespace hsmap
