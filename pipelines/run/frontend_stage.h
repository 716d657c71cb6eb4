#pragma once
// The frontend stage: the RGB frames -> RUN/frontend/ (docs/FRONTEND.md).

#include "pipelines/run/stage_context.h"

namespace hsmap {

void runFrontendStage(const StageContext& context);

}  // namespace hsmap
