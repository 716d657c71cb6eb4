#include "pipelines/run/georef_stage.h"

#include <optional>
#include <ostream>
#include <string>

#include "core/util/progress.h"
#include "pipelines/frontend/frontend_outputs.h"
#include "pipelines/georef/georef_outputs.h"
#include "pipelines/georef/planar_georef.h"
#include "pipelines/georef/sequential_georef.h"

namespace hsmap {

void runGeorefStage(const StageContext& context) {
  std::ostream& out = context.out;
  const GeorefOptions options;
  GeorefResult result;
  if (context.variant == Variant::planar) {
    result = runPlanarGeoref(context.survey, options);
  } else {
    out << "georef: reading the front-end's files from " << (context.run / frontend_files::folder).string()
        << "\n";
    const FrontendResult frontend = readFrontendOutputs(context.run);
    std::optional<Progress> frames;
    result = runSequentialGeoref(context.survey, frontend, options,
                                 [&](const std::string& step, int done, int total) {
                                   if (step != "frames") {
                                     if (done == 0) out << "georef: " << step << "...\n";
                                     return;
                                   }
                                   if (!frames) frames.emplace("georef: posing frames", total, "frames", out);
                                   frames->advance(done - frames->done());
                                 });
    if (frames) frames->finish();
  }
  // The joint variant starts from the sequential result: the same files
  // (labelled sequential) whichever variant runs the stage, so that a georef
  // folder serves both (stage_fingerprints.h). The joint stage replaces them
  // in the contract's paths; a joint run stopped before it publishes them
  // relabelled (published_calibration.h).
  const auto folder = context.run / stage_folders::georef;
  writeGeorefOutputs(folder, result);
  out << result.summary() << "\n";
  for (const auto& warning : result.warnings) out << "warning: " << warning << "\n";
  out << "wrote " << folder.string() << "/\n";
}

}  // namespace hsmap
