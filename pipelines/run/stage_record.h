#pragma once
// RUN/stages/<stage>.yaml: the record a stage leaves when it has finished,
// written last (atomically), after every file it owns is in place. A run on
// an existing folder skips a stage whose record is there, whose fingerprint
// still matches and whose files are all present with the recorded sizes
// (docs/RUN.md, "Resuming"):
//
//   format: hsmap-stage/1
//   stage: georef
//   variant: sequential
//   survey: /absolute/path/to/survey
//   fingerprint: 9f3c0a51d2e4b786      the stage's options, the survey's files
//                                      (names, sizes, times) and the previous
//                                      stage's fingerprint, hashed
//   options: "variant: sequential\n"   what the fingerprint covers of the options
//   time_s: 3.2
//   peak_rss_mb: 300.0
//   outputs:                           every file the stage owns, with its size
//     - {path: georef/frames.csv, bytes: 123456}
//
// A record that cannot be read is no record: the stage runs again (the
// reason is printed), nothing is lost but time.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace hsmap {

struct StageOutputFile {
  std::string path;  // relative to RUN, '/' separated
  std::uintmax_t bytes = 0;
};

struct StageRecordFile {
  static constexpr const char* kFormat = "hsmap-stage/1";
  std::string stage;
  std::string variant;
  std::string survey;
  std::string fingerprint;
  std::string options;
  double time_s = 0.0;
  double peak_rss_mb = 0.0;
  std::vector<StageOutputFile> outputs;
};

std::filesystem::path stageRecordPath(const std::filesystem::path& run, const std::string& stage);

// Atomic. Throws std::runtime_error on an I/O failure.
void writeStageRecord(const std::filesystem::path& file, const StageRecordFile& record);
// nullopt when the file is absent or unreadable; `why` then says which.
std::optional<StageRecordFile> readStageRecord(const std::filesystem::path& file, std::string& why);

// Every regular file under `outputs` (files or folders relative to `run`),
// sorted by path, with its size.
std::vector<StageOutputFile> listStageOutputs(const std::filesystem::path& run,
                                              const std::vector<std::filesystem::path>& outputs);

// The survey's input files (everything under `survey` but truth/ and the
// run folder `run`, should it lie inside): their names, sizes and
// modification times, one line each, sorted.
std::string surveyStamp(const std::filesystem::path& survey, const std::filesystem::path& run);

// A 64-bit FNV-1a hash of `text`, as 16 hex digits.
std::string fingerprintOf(const std::string& text);

}  // namespace hsmap
