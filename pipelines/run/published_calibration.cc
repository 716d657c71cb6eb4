#include "pipelines/run/published_calibration.h"

#include "core/io/published_file.h"
#include "core/survey/run_calibration.h"

namespace hsmap {

void publishCalibration(const std::filesystem::path& from, const std::filesystem::path& to,
                        const std::string& variant) {
  RunCalibration calibration = readRunCalibration(from);
  if (calibration.variant == variant) {
    publishFile(from, to);
    return;
  }
  calibration.variant = variant;
  // Atomic (a rename onto `to`): a link there to another stage's file is
  // replaced, never written through.
  writeRunCalibration(to, calibration);
}

}  // namespace hsmap
