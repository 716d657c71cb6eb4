#include "pipelines/run/frontend_stage.h"

#include <ostream>

#include "core/util/progress.h"
#include "pipelines/frontend/frontend_outputs.h"
#include "pipelines/frontend/frontend_runner.h"

namespace hsmap {

void runFrontendStage(const StageContext& context) {
  std::ostream& out = context.out;
  const FrontendOptions options;
  Progress progress("frontend", context.survey.rgb.frameCount(), "frames", out);
  int reported = 0;
  const FrontendResult result = runFrontend(context.survey, options, [&](int done, int, double) {
    progress.advance(done - reported);
    reported = done;
  });
  progress.finish();
  writeFrontendOutputs(context.run, result);
  out << result.summary() << "\n";
  for (const auto& warning : result.warnings) out << "warning: " << warning << "\n";
  out << "wrote " << (context.run / frontend_files::folder).string() << "/\n";
}

}  // namespace hsmap
