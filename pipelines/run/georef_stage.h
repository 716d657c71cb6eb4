#pragma once
// The georef stage: RUN/frontend/ and the INS (sequential, joint) or the INS
// alone (planar) -> RUN/georef/ (georef_outputs.h; docs/GEOREF.md).

#include "pipelines/run/stage_context.h"

namespace hsmap {

void runGeorefStage(const StageContext& context);

}  // namespace hsmap
