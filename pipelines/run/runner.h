#pragma once
// The runner of `hsmap run` (docs/RUN.md): checks the options, loads the
// survey once, and runs the variant's stages (stage_table.h) in order into
// the run folder, each a function of its options and the folder.
//
// Resuming, as users of COLMAP and OpenMVS expect: on an existing run folder
// a stage whose record (stage_record.h) is present, whose fingerprint (its
// options, the survey's files, the previous stage's fingerprint) matches and
// whose files are all there is skipped, and said so; the first stage that is
// not up to date runs, and every stage after it. `--from X` redoes X and the
// stages after it (the stages before must be up to date); `--force` redoes
// every stage; `--until X` stops after X. Before a stage runs, its files and
// those of the stages after it are removed, with run.yaml and metrics.json:
// a folder never holds a product that looks complete but is not the run's.
// run.yaml is written last, when every stage asked for has succeeded.
//
// A folder holding another survey's run, or products that no stage record
// accounts for (a run by an older hsmap), is replaced only with --force.

#include <iosfwd>

#include "pipelines/run/run_options.h"

namespace hsmap {

// Exit status: 0 on success; 1 for a usage error or a stage that fails
// (reported on `err`). InputError (a bad survey or run folder file)
// propagates to the caller (status 2 for `hsmap`).
int runStages(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace hsmap
