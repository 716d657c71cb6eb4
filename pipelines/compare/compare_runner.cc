#include "pipelines/compare/compare_runner.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <mutex>
#include <optional>
#include <ostream>

#include "core/io/results_folder.h"
#include "core/survey/run_record.h"
#include "core/survey/survey_config.h"
#include "core/util/input_error.h"
#include "pipelines/compare/compare_csv.h"
#include "pipelines/compare/compare_html.h"
#include "pipelines/compare/compare_markdown.h"
#include "pipelines/compare/compare_plan.h"
#include "pipelines/compare/compare_schedule.h"
#include "pipelines/compare/metrics_file.h"
#include "pipelines/compare/stage_sharing.h"
#include "pipelines/run/stage_record.h"

namespace hsmap {

namespace fs = std::filesystem;

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string seconds(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f s", value);
  return text;
}

// A child's output: all of it to the variant's log, its stage lines to the
// terminal as they complete, and its last error line kept for the table.
class ChildOutput {
 public:
  ChildOutput(std::ofstream& log, std::function<void(const std::string&)> say, std::string prefix)
      : log_(log), say_(std::move(say)), prefix_(std::move(prefix)) {}

  void operator()(std::string_view chunk) {
    log_ << chunk;
    log_.flush();
    for (char c : chunk) {
      if (c != '\n') {
        line_ += c;
        continue;
      }
      take(line_);
      line_.clear();
    }
  }
  // The last "error: ..." line's text, if any.
  const std::string& lastError() {
    if (!line_.empty()) take(line_), line_.clear();
    return last_error_;
  }

 private:
  void take(const std::string& line) {
    if (line.starts_with("error: ")) last_error_ = line.substr(7);
    // The runner's "stage X" lines (not its closing "stage times ..." table).
    const bool stage_line = line.starts_with("stage ") && !line.starts_with("stage times");
    if (stage_line || line.starts_with("error: ")) say_(prefix_ + line);
  }

  std::ofstream& log_;
  std::function<void(const std::string&)> say_;
  std::string prefix_;
  std::string line_;
  std::string last_error_;
};

std::string whyFailed(const std::string& command, int status, const std::string& last_error) {
  if (!last_error.empty()) return last_error;
  if (status > 128) return "hsmap " + command + " was ended by signal " + std::to_string(status - 128);
  return "hsmap " + command + " exited with status " + std::to_string(status);
}

std::string stageNames(const std::vector<StageId>& stages) {
  std::string text;
  for (StageId stage : stages) text += (text.empty() ? "" : ", ") + std::string(stageDefinition(stage).name);
  return text;
}

}  // namespace

int runCompare(const CompareOptions& options, const HsmapCommand& hsmap, std::ostream& out, std::ostream& err) {
  const auto started = std::chrono::steady_clock::now();
  if (options.variants.empty()) {
    err << "error: --variants: expected at least one variant\n";
    return 1;
  }
  if (options.jobs < 1) {
    err << "error: --jobs: expected 1 or more runs at a time, got " << options.jobs << "\n";
    return 1;
  }
  if (options.threads < 0) {
    err << "error: --threads: expected 0 (every hardware thread) or more, got " << options.threads << "\n";
    return 1;
  }
  const fs::path survey = fs::absolute(options.survey).lexically_normal();
  const fs::path dir = fs::absolute(options.out).lexically_normal();
  readSurveyConfig(survey / "survey.yaml");  // an invalid survey stops here (InputError), not four times
  const fs::path inside = dir.lexically_relative(survey);
  if (!inside.empty() && *inside.begin() != "..") {
    err << "error: --out " << options.out.string() << " lies inside the survey folder " << survey.string()
        << ": the variants' runs would change the survey's files as each other sees them; choose a folder "
           "outside it\n";
    return 1;
  }
  std::error_code error;
  if (fs::exists(dir, error) && !fs::is_directory(dir, error)) {
    err << "error: --out " << options.out.string() << " exists and is not a folder\n";
    return 1;
  }
  fs::create_directories(dir);
  const bool has_truth = fs::is_directory(survey / "truth", error);

  RunOptions base;
  base.survey = survey;
  base.threads = options.threads;
  const std::vector<VariantPlan> plans = planCompare(options.variants, base, surveyStamp(survey, dir));
  out << "compare: " << plans.size() << " variant" << (plans.size() == 1 ? "" : "s") << " of " << survey.string()
      << " into " << dir.string() << (has_truth ? ", each evaluated" : " (no truth/: not evaluated)") << "\n";
  for (const VariantPlan& plan : plans) {
    if (plan.donor) {
      out << "compare: " << toString(plan.variant) << " takes " << stageNames(plan.shared) << " from "
          << toString(*plan.donor) << " (the same stages, options and survey)\n";
    }
  }

  // Each variant's state while its steps run (one step of a variant at a
  // time: the second waits for the first).
  struct VariantState {
    VariantOutcome outcome;
    std::ofstream log;
    std::optional<std::chrono::steady_clock::time_point> started;
  };
  std::vector<VariantState> states(plans.size());
  for (std::size_t v = 0; v < plans.size(); ++v) {
    const std::string name = toString(plans[v].variant);
    states[v].outcome.variant = name;
    states[v].log.open(dir / (name + ".log"), std::ios::trunc);
    if (!states[v].log) {
      err << "error: " << (dir / (name + ".log")).string() << ": cannot open the file for writing\n";
      return 1;
    }
  }
  std::mutex out_mutex;  // the steps' lines, whole, one at a time
  auto say = [&](const std::string& line) {
    std::lock_guard lock(out_mutex);
    out << line << "\n" << std::flush;
  };

  const std::vector<CompareTask> tasks = scheduleCompare(plans);
  auto run_task = [&](std::size_t t) {
    const CompareTask& task = tasks[t];
    const VariantPlan& plan = plans[task.variant];
    VariantState& state = states[task.variant];
    VariantOutcome& outcome = state.outcome;
    const std::string name = outcome.variant;
    const fs::path run = dir / name;
    if (!outcome.succeeded()) return;  // its first step failed
    if (!state.started) state.started = std::chrono::steady_clock::now();
    say("[" + name + "] " + (task.until.empty() ? "running" : "running up to " + task.until + " (shared)") +
        " into " + run.string() + " (log " + (dir / (name + ".log")).string() + ")");

    std::vector<std::string> arguments = {"run", survey.string(), "--out", run.string(), "--variant", name,
                                          "--threads", std::to_string(options.threads)};
    if (!task.until.empty()) arguments.insert(arguments.end(), {"--until", task.until});
    // The stages this step starts at: the first not shared (nor already run
    // by this variant's first step); --force redoes from there only, so a
    // shared stage is still run once.
    std::size_t from = 0;
    std::optional<std::size_t> after_own_step;  // the second step of a donor: after its shared stages
    for (const CompareTask& other : tasks) {
      if (task.until.empty() && other.variant == task.variant && !other.until.empty()) {
        after_own_step = std::size_t(stageIndex(variantStages(plan.variant), other.until)) + 1;
      }
    }
    if (after_own_step) {
      from = *after_own_step;
    } else if (plan.donor && !plan.shared.empty()) {
      const fs::path donor = dir / toString(*plan.donor);
      for (StageId stage : plan.shared) {
        std::string why;
        try {
          if (!shareStage(donor, run, stage, why)) {
            outcome.status = "failed: not run: its stage " + std::string(stageDefinition(stage).name) +
                             ", shared with " + toString(*plan.donor) + ", did not finish there (see " +
                             (dir / (std::string(toString(*plan.donor)) + ".log")).string() + ")";
            break;
          }
        } catch (const std::exception& failure) {
          outcome.status = "failed: sharing its stage " + std::string(stageDefinition(stage).name) + " from " +
                           toString(*plan.donor) + ": " + failure.what();
          break;
        }
        outcome.shared_stages.push_back(stageDefinition(stage).name);
      }
      outcome.shared_from = toString(*plan.donor);
      if (!outcome.succeeded()) {
        say("[" + name + "] " + outcome.status);
        return;
      }
      say("[" + name + "] " + stageNames(plan.shared) + " linked in from " + donor.string());
      from = plan.shared.size();
    }
    if (options.force) {
      const auto& stages = variantStages(plan.variant);
      if (from == 0) {
        arguments.push_back("--force");
      } else if (from < stages.size()) {
        arguments.insert(arguments.end(), {"--from", stageDefinition(stages[from]).name});
      }
    }

    ChildOutput output(state.log, say, "  " + name + " | ");
    const int status = hsmap(arguments, [&](std::string_view chunk) { output(chunk); });
    if (status != 0) outcome.status = "failed: " + whyFailed("run", status, output.lastError());
    if (!task.until.empty()) return;  // the rest, and the evaluation, in its second step

    std::error_code ignored;
    if (outcome.succeeded() && has_truth) {
      ChildOutput evaluation(state.log, say, "  " + name + " | ");
      const int evaluated = hsmap({"evaluate", run.string(), "--truth", (survey / "truth").string()},
                                  [&](std::string_view chunk) { evaluation(chunk); });
      if (evaluated != 0) {
        outcome.status = "failed: evaluate: " + whyFailed("evaluate", evaluated, evaluation.lastError());
      }
    }
    outcome.wall_time_s = secondsSince(*state.started);
    // What the run and the evaluation left, as far as they got.
    try {
      if (fs::is_regular_file(run / results_paths::run_yaml, ignored)) {
        for (const StageRecord& stage : readRunRecord(run / results_paths::run_yaml).stages) {
          outcome.stages.push_back({stage.name, stage.time_s});
        }
      }
      if (outcome.succeeded() && has_truth) outcome.metrics = readMetricsFile(run / results_paths::metrics_json);
    } catch (const InputError& failure) {
      outcome.status = std::string("failed: ") + failure.what();
    }
    if (fs::is_regular_file(run / results_paths::ortho_rgb_png, ignored)) {
      outcome.quicklook = run / results_paths::ortho_rgb_png;
    }
    say("[" + name + "] " + outcome.status + " in " + seconds(outcome.wall_time_s));
  };
  runTaskGraph(tasks, options.jobs, [&](std::size_t t) {
    try {
      run_task(t);
    } catch (const std::exception& failure) {  // e.g. the process could not be started
      states[tasks[t].variant].outcome.status = std::string("failed: ") + failure.what();
    }
  });
  // A variant that failed in its first step never reached the second: its
  // time is up to the failure.
  std::vector<VariantOutcome> outcomes;
  for (VariantState& state : states) {
    if (state.started && state.outcome.wall_time_s == 0.0) state.outcome.wall_time_s = secondsSince(*state.started);
    if (!state.outcome.succeeded()) {
      std::error_code ignored;
      const fs::path run = dir / state.outcome.variant;
      try {
        if (state.outcome.stages.empty() && fs::is_regular_file(run / results_paths::run_yaml, ignored)) {
          for (const StageRecord& stage : readRunRecord(run / results_paths::run_yaml).stages) {
            state.outcome.stages.push_back({stage.name, stage.time_s});
          }
        }
      } catch (const InputError&) {
      }
    }
    outcomes.push_back(std::move(state.outcome));
  }

  const CompareTable table = buildCompareTable(std::move(outcomes));
  // The compare's wall time up to its tables (writing them takes well under a second).
  const CompareReportContext context{survey, dir, secondsSince(started), has_truth};
  writeCompareCsv(dir / "compare.csv", table);
  writeCompareMarkdown(dir / "compare.md", table, context);
  writeCompareHtml(dir / "compare.html", table, context);

  int failed = 0;
  out << "compare: wrote " << (dir / "compare.csv").string() << ", compare.md and compare.html in "
      << seconds(context.wall_time_s) << "\n";
  for (const VariantOutcome& variant : table.variants) {
    char line[64];
    std::snprintf(line, sizeof(line), "  %-11s %9s  ", variant.variant.c_str(),
                  seconds(variant.wall_time_s).c_str());
    out << line << variant.status;
    if (!variant.shared_stages.empty()) {
      out << " (took " << variant.shared_stages.size() << " stages from " << variant.shared_from << ")";
    }
    out << "  " << (dir / variant.variant).string() << "\n";
    failed += variant.succeeded() ? 0 : 1;
  }
  if (failed > 0) {
    err << "error: " << failed << " of " << table.variants.size() << " variants failed; each says why in "
        << (dir / "compare.md").string() << " and its log\n";
    return 1;
  }
  return 0;
}

}  // namespace hsmap
