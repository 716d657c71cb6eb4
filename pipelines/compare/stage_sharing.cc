#include "pipelines/compare/stage_sharing.h"

#include "pipelines/run/stage_record.h"

namespace hsmap {

namespace fs = std::filesystem;

namespace {

void linkOrCopy(const fs::path& from, const fs::path& to) {
  fs::create_directories(to.parent_path());
  std::error_code error;
  fs::create_hard_link(from, to, error);
  if (error) fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}

}  // namespace

bool shareStage(const fs::path& donor, const fs::path& recipient, StageId stage, std::string& why) {
  const StageDefinition& definition = stageDefinition(stage);
  const fs::path donor_record = stageRecordPath(donor, definition.name);
  const auto record = readStageRecord(donor_record, why);
  if (!record) return false;

  const fs::path recipient_record = stageRecordPath(recipient, definition.name);
  fs::remove(recipient_record);
  for (const fs::path& output : definition.outputs) fs::remove_all(recipient / output);
  // The files the record lists: exactly what the recipient's runner checks.
  for (const StageOutputFile& output : record->outputs) linkOrCopy(donor / output.path, recipient / output.path);
  fs::create_directories(recipient_record.parent_path());
  const fs::path partial = recipient_record.string() + ".partial";
  fs::copy_file(donor_record, partial, fs::copy_options::overwrite_existing);
  fs::rename(partial, recipient_record);
  return true;
}

}  // namespace hsmap
