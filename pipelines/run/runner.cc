#include "pipelines/run/runner.h"

#include <opencv2/core/utility.hpp>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "core/io/published_file.h"
#include "core/io/results_folder.h"
#include "core/survey/number_text.h"
#include "core/survey/run_record.h"
#include "core/survey/survey.h"
#include "core/util/input_error.h"
#include "core/util/stage_timer.h"
#include "core/util/tee_stream.h"
#include "core/util/thread_budget.h"
#include "pipelines/georef/georef_outputs.h"
#include "pipelines/run/estimated_rgb_camera.h"
#include "pipelines/run/published_calibration.h"
#include "pipelines/run/stage_fingerprints.h"
#include "pipelines/report/run_report.h"
#include "pipelines/run/stage_record.h"
#include "pipelines/run/stage_table.h"

#ifndef HSMAP_VERSION
#define HSMAP_VERSION "unknown"
#endif

namespace hsmap {

namespace fs = std::filesystem;

namespace {

std::string secondsText(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f s", seconds);
  return text;
}

std::string megabytesText(double mb) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.0f MiB", mb);
  return text;
}

// Whether stage `name`'s record in `run` says it is finished with
// `fingerprint` and its files are all there; `why` says what is not.
bool upToDate(const fs::path& run, const std::string& name, const std::string& fingerprint,
              const std::string& options_text, std::optional<StageRecordFile>& record, std::string& why) {
  record = readStageRecord(stageRecordPath(run, name), why);
  if (!record) return false;
  if (record->fingerprint != fingerprint) {
    why = record->options != options_text
              ? "its options changed (were: " + record->options + "now: " + options_text + ")"
              : "the survey's files or an earlier stage changed since it ran";
    for (char& c : why) c = c == '\n' ? ';' : c;
    return false;
  }
  for (const StageOutputFile& output : record->outputs) {
    std::error_code error;
    const fs::path path = run / output.path;
    const std::uintmax_t bytes = fs::file_size(path, error);
    if (error) {
      why = path.string() + " is missing";
      return false;
    }
    if (bytes != output.bytes) {
      why = path.string() + " has " + std::to_string(bytes) + " bytes, not the " + std::to_string(output.bytes) +
            " the stage wrote";
      return false;
    }
  }
  return true;
}

// The stage's record first (so a stage half removed is never up to date),
// then its files.
void removeStage(const fs::path& run, const StageDefinition& stage) {
  fs::remove(stageRecordPath(run, stage.name));
  for (const fs::path& path : stage.outputs) fs::remove_all(run / path);
}

void publish(const fs::path& run, const StageDefinition& stage, Variant variant) {
  for (const auto& [owned, contract] : stage.published) {
    std::error_code error;
    if (!fs::is_regular_file(run / owned, error)) continue;
    if (contract == results_paths::calibration_yaml) {
      publishCalibration(run / owned, run / contract, toString(variant));
    } else {
      publishFile(run / owned, run / contract);
    }
  }
}

// The report last, from the run folder as the stages left it (also after a
// stage failed: it shows what finished). It is not a product of a stage: a
// report that cannot be written is said, and the run's files stay as they are.
void reportRun(const fs::path& run, std::ostream& out, std::ostream& err) {
  try {
    const RunReport report = writeRunReport(run);
    out << "report: " << report.path.string() << "\n";
  } catch (const std::exception& failure) {
    err << "warning: the run's report was not written (the run's files are complete): " << failure.what() << "\n";
  }
}

int runStagesLogged(const RunOptions& options, std::ostream& out, std::ostream& err) {
  try {
    options.validate();
  } catch (const std::invalid_argument& failure) {
    err << "error: " << failure.what() << "\n";
    return 1;
  }
  if (const std::string ignored = ignoredOptionError(options); !ignored.empty()) {
    err << "error: " << ignored << "\n";
    return 1;
  }
  const std::vector<StageId>& stages = variantStages(options.variant);
  const int last = options.until.empty() ? int(stages.size()) - 1 : stageIndex(stages, options.until);
  const int from = options.from.empty() ? 0 : stageIndex(stages, options.from);
  for (const auto& [flag, name, index] :
       {std::tuple{"--until", options.until, last}, std::tuple{"--from", options.from, from}}) {
    if (index < 0) {
      err << "error: unknown stage '" << name << "' for " << flag << "; the " << toString(options.variant)
          << " variant runs " << stageList(stages) << "\n";
      return 1;
    }
  }
  if (from > last) {
    err << "error: --from " << options.from << " comes after --until " << options.until << "\n";
    return 1;
  }
  const fs::path& run = options.out;
  std::error_code error;
  if (fs::exists(run, error) && !fs::is_directory(run, error)) {
    err << "error: " << run.string() << " exists and is not a folder\n";
    return 1;
  }

  setThreadBudget(options.threads);
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, std::size_t(threadBudget()));
  // OpenCV's own thread pool (optical flow, stereo matching) under the same budget.
  cv::setNumThreads(threadBudget());

  RunRecord record;
  record.program_version = HSMAP_VERSION;
  record.variant = toString(options.variant);
  record.survey = fs::absolute(options.survey).lexically_normal();
  record.started_utc = formatUtcTimestamp(std::chrono::system_clock::now());
  const auto started = std::chrono::steady_clock::now();

  auto load_start = std::chrono::steady_clock::now();
  Survey survey = loadSurvey(options.survey);  // its RGB camera: georef's estimate after georef
  record.stages.push_back({"load", secondsSince(load_start), peakResidentMemoryMb()});
  out << "survey '" << survey.config.name << "': " << survey.rgb.frameCount() << " RGB frames, "
      << survey.line_times.size() << " scan lines, " << survey.ins.fixes.size() << " INS fixes ("
      << (survey.ins.has_attitude ? "with" : "without") << " attitude)\n";
  for (const auto& warning : survey.warnings) out << "warning: " << warning << "\n";

  // Each stage's fingerprint: its options, the survey's files and the
  // previous stage's fingerprint.
  std::vector<std::string> fingerprints, options_texts;
  for (const StageFingerprint& stage : stageFingerprints(options, surveyStamp(options.survey, run))) {
    options_texts.push_back(stage.options_text);
    fingerprints.push_back(stage.fingerprint);
  }
  const int stage_count = int(stages.size());

  // Another survey's run is replaced only on purpose.
  for (StageId id : allStages()) {
    std::string why;
    const auto earlier = readStageRecord(stageRecordPath(run, stageDefinition(id).name), why);
    if (earlier && earlier->survey != record.survey.string() && !options.force) {
      err << "error: " << run.string() << " holds a run of the survey " << earlier->survey
          << " (" << stageRecordPath(run, stageDefinition(id).name).string()
          << "); pass --force to replace it, or choose another --out\n";
      return 1;
    }
  }

  // The first stage to run: --from's, or (resuming) the first not up to date.
  std::vector<std::optional<StageRecordFile>> records(std::size_t(last) + 1);
  int first = 0;
  if (!options.from.empty()) {
    first = from;
    for (int i = 0; i < first; ++i) {
      const char* name = stageDefinition(stages[std::size_t(i)]).name;
      std::string why;
      if (!upToDate(run, name, fingerprints[std::size_t(i)], options_texts[std::size_t(i)], records[std::size_t(i)],
                    why)) {
        err << "error: --from " << options.from << " starts from the files of the stages before it, but stage "
            << name << " in " << run.string() << " is not up to date: " << why << "; start at --from " << name
            << " (or leave --from out to resume from the first stage not up to date)\n";
        return 1;
      }
    }
  } else if (!options.force) {
    while (first <= last) {
      const char* name = stageDefinition(stages[std::size_t(first)]).name;
      std::string why;
      if (!upToDate(run, name, fingerprints[std::size_t(first)], options_texts[std::size_t(first)],
                    records[std::size_t(first)], why)) {
        if (records[std::size_t(first)] || first > 0) out << "stage " << name << ": runs again: " << why << "\n";
        break;
      }
      ++first;
    }
  }

  // Files no stage record accounts for, in a folder with no record at all
  // (a run by an older hsmap, a copy, someone's own files), are replaced only
  // on purpose. A folder with records was written by this runner: what a
  // killed stage left is its own and goes (its unfinished files end in
  // .partial anyway).
  bool any_record = false;
  for (StageId id : allStages()) {
    std::error_code exists_error;
    any_record = any_record || fs::exists(stageRecordPath(run, stageDefinition(id).name), exists_error);
  }
  for (int i = first; i < int(stages.size()) && !options.force && !any_record; ++i) {
    const StageDefinition& stage = stageDefinition(stages[std::size_t(i)]);
    for (const StageOutputFile& file : listStageOutputs(run, stage.outputs)) {
      if (file.path.ends_with(".partial")) continue;
      err << "error: " << (run / file.path).string() << " exists from an earlier run that left no record of its "
          << stage.name << " stage; pass --force to replace it\n";
      return 1;
    }
  }

  // From here the folder changes: what is about to be redone, and all that
  // follows from it, goes first.
  fs::create_directories(run);
  for (const fs::path path : {fs::path(results_paths::run_yaml), fs::path(results_paths::metrics_json)}) {
    fs::remove_all(run / path);
  }
  for (const fs::path& path : publishedContractPaths()) fs::remove_all(run / path);
  for (StageId id : allStages()) {
    const StageDefinition& stage = stageDefinition(id);
    const int index = stageIndex(stages, stage.name);
    if (index >= 0 && index < first) continue;  // kept
    // Nothing to run (all up to --until is up to date): the stages after
    // --until are checked after the loop, not removed.
    if (index >= 0 && first > last) continue;
    removeStage(run, stage);
  }

  const StageContext context{survey, run, options.variant, out};
  for (int i = 0; i <= last; ++i) {
    const StageDefinition& stage = stageDefinition(stages[std::size_t(i)]);
    // The stages after georef use the RGB camera it estimated (rgb.camera_sigma).
    if (i > 0 && std::string(stageDefinition(stages[std::size_t(i - 1)]).name) == stage_folders::georef) {
      useEstimatedRgbCamera(survey, run / stage_folders::georef / georef_files::calibration, out);
    }
    if (i < first) {
      const StageRecordFile& done = *records[std::size_t(i)];
      out << "stage " << stage.name << ": up to date, skipped (ran in " << secondsText(done.time_s)
          << "; --force or --from " << stage.name << " redoes it)\n";
      record.stages.push_back({stage.name, done.time_s, done.peak_rss_mb});
      publish(run, stage, options.variant);
      continue;
    }
    out << "stage " << stage.name << "\n";
    const auto stage_start = std::chrono::steady_clock::now();
    try {
      stage.run(context, options);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& failure) {
      err << "error: stage " << stage.name << " failed: " << failure.what() << "\n";
      reportRun(run, out, err);
      return 1;
    }
    StageRecordFile done;
    done.stage = stage.name;
    done.variant = toString(options.variant);
    done.survey = record.survey.string();
    done.fingerprint = fingerprints[std::size_t(i)];
    done.options = options_texts[std::size_t(i)];
    done.time_s = secondsSince(stage_start);
    done.peak_rss_mb = peakResidentMemoryMb();
    done.outputs = listStageOutputs(run, stage.outputs);
    writeStageRecord(stageRecordPath(run, stage.name), done);
    record.stages.push_back({stage.name, done.time_s, done.peak_rss_mb});
    publish(run, stage, options.variant);
  }

  // When nothing ran, the stages after --until that are still up to date
  // stay, published, so the contract's files match the products beside
  // them; from the first that is not, they go.
  if (first > last) {
    for (int i = last + 1; i < stage_count; ++i) {
      const StageDefinition& stage = stageDefinition(stages[std::size_t(i)]);
      std::optional<StageRecordFile> later;
      std::string why;
      if (upToDate(run, stage.name, fingerprints[std::size_t(i)], options_texts[std::size_t(i)], later, why)) {
        publish(run, stage, options.variant);
        continue;
      }
      for (int j = i; j < stage_count; ++j) removeStage(run, stageDefinition(stages[std::size_t(j)]));
      break;
    }
  }

  record.options["until"] = stageDefinition(stages[std::size_t(last)]).name;
  record.options["from"] = first <= last ? stageDefinition(stages[std::size_t(first)]).name : "";
  record.options["threads"] = std::to_string(options.threads);
  for (int i = 0; i <= last; ++i) {
    // The options each stage ran with, as "key: value" lines.
    std::string text = options_texts[std::size_t(i)];
    for (std::size_t start = 0; start < text.size();) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      const std::string line = text.substr(start, end - start);
      const std::size_t colon = line.find(": ");
      if (colon != std::string::npos) record.options[line.substr(0, colon)] = line.substr(colon + 2);
      start = end + 1;
    }
  }
  record.total_time_s = secondsSince(started);
  record.peak_rss_mb = peakResidentMemoryMb();
  writeRunRecord(run / results_paths::run_yaml, record);

  out << "stage times and peak memory (of the process when the stage ended):\n";
  for (std::size_t s = 0; s < record.stages.size(); ++s) {
    const auto& stage = record.stages[s];
    const bool skipped = s >= 1 && int(s) - 1 < first;
    char line[160];
    std::snprintf(line, sizeof(line), "  %-10s %10s %10s%s\n", stage.name.c_str(), secondsText(stage.time_s).c_str(),
                  megabytesText(stage.peak_rss_mb).c_str(), skipped ? "  (up to date, from its record)" : "");
    out << line;
  }
  out << "total " << secondsText(record.total_time_s) << ", peak memory " << megabytesText(record.peak_rss_mb)
      << "; the run is in " << run.string() << " (run.yaml written)\n";
  reportRun(run, out, err);
  return 0;
}

}  // namespace

int runStages(const RunOptions& options, std::ostream& out, std::ostream& err) {
  if (options.log.empty()) return runStagesLogged(options, out, err);
  std::ofstream log(options.log, std::ios::app);
  if (!log) {
    err << "error: --log " << options.log.string() << ": cannot open the file for writing\n";
    return 1;
  }
  TeeStream log_out(out, log), log_err(err, log);
  const int status = runStagesLogged(options, log_out, log_err);
  log_out.flush();
  log_err.flush();
  return status;
}

}  // namespace hsmap
