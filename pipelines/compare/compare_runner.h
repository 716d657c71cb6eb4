#pragma once
// `hsmap compare SURVEY --out DIR` (docs/COMPARE.md): runs each variant into
// DIR/<variant> with `hsmap run`, up to `jobs` runs at a time
// (compare_schedule.h), a variant taking the stages it shares with an
// earlier one from that one's run folder (compare_plan.h, stage_sharing.h),
// so the front-end runs once and joint starts from sequential's georef and
// surface as soon as they are done; evaluates each run when the
// survey has truth/ (`hsmap evaluate`); and writes DIR/compare.csv,
// compare.md and compare.html (compare_table.h and its writers).
//
// Each variant runs as its own `hsmap` process: its time and peak memory are
// its own, and a variant that fails, even by a crash, is a column of the
// table saying why while the others still run. Its output goes to
// DIR/<variant>.log; the compare prints its stage lines as they come.
// On an existing DIR every run resumes (docs/RUN.md): finished stages are
// skipped.

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "pipelines/run/run_options.h"

namespace hsmap {

struct CompareOptions {
  std::filesystem::path survey;
  std::filesystem::path out;
  std::vector<Variant> variants;  // in the table's order (variant_list.h)
  int threads = 0;                // handed to every run (0: every hardware thread)
  bool force = false;             // redo every stage (a shared stage still runs once)
  int jobs = 2;                   // runs at a time (compare_schedule.h)
};

// Runs `hsmap <arguments>` and hands its output (stdout and stderr merged) to
// `output` as it comes; returns the exit status (128 + the signal's number
// when a signal ended it).
using HsmapOutput = std::function<void(std::string_view chunk)>;
using HsmapCommand = std::function<int(const std::vector<std::string>& arguments, const HsmapOutput& output)>;

// Exit status: 0 when every variant ran (and was evaluated, with truth);
// 1 for a usage error (on `err`) or when a variant failed (the table is
// written all the same and says why). InputError (the survey is not valid)
// propagates (status 2 for `hsmap`).
int runCompare(const CompareOptions& options, const HsmapCommand& hsmap, std::ostream& out, std::ostream& err);

}  // namespace hsmap
