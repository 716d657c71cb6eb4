#include "factors/spline_pose_factor.h"

#include <ceres/autodiff_cost_function.h>

#include <cstdint>
#include <vector>

#include "core/graph/key.h"
#include "factors/factor_argument_checks.h"
#include "factors/spline_timing.h"

namespace hsmap {

namespace {

constexpr int P = SE3d::kNumParameters;

}  // namespace

SplinePoseFactor::SplinePoseFactor(const SplineTiming& spline, double t,
                                   const SE3d& T_W_C_measured, NoiseModel noise,
                                   RobustLoss robust_loss)
    : CeresFactor(activeControlPointKeys(spline.segmentAt(t)), std::move(noise), robust_loss),
      t_(t),
      segment_(spline.segmentAt(t)),
      T_W_C_measured_(requireRigidTransform("SplinePoseFactor", "measured pose T_W_C",
                                            T_W_C_measured)) {
  requireNoiseDimension("SplinePoseFactor", this->noise(), kResidualDimension);
}

std::unique_ptr<ceres::CostFunction> SplinePoseFactor::createCostFunction() const {
  return std::make_unique<
      ceres::AutoDiffCostFunction<SplinePoseResidual, kResidualDimension, P, P, P, P>>(
      new SplinePoseResidual{segment_.u, T_W_C_measured_.inverse()});
}

}  // namespace hsmap
