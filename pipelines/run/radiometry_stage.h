#pragma once
// The radiometry stage: the water's attenuation c(λ), the lamps' beam and the
// backscatter estimated from the survey itself (docs/RADIOMETRY.md).
//
//   reads   RUN/trajectory/uhi_lines.csv, RUN/map/mesh.ply, RUN/calibration.yaml
//           (T_C_U, the UHI camera) as published by the stages before it; the
//           survey's cube and `lights` (lamps and K(λ))
//   writes  RUN/radiometry/water.yaml (core/survey/water_estimate.h),
//           RUN/radiometry/calibration.yaml (the run's calibration.yaml with
//           the contract's `water:` block and the stage's warnings, published
//           as RUN/calibration.yaml) and
//           RUN/radiometry/summary.txt; the products stage turns the
//           radiance ortho into reflectance with it
// A survey without `lights` gets no estimate (and so radiance products only),
// and the stage says why.

#include "pipelines/radiometry/radiometry_files.h"
#include "pipelines/run/stage_context.h"

namespace hsmap {

void runRadiometryStage(const StageContext& context);

}  // namespace hsmap
