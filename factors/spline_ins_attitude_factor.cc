#include "factors/spline_ins_attitude_factor.h"

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

SplineInsAttitudeFactor::SplineInsAttitudeFactor(const SplineTiming& spline, double t_fix,
                                                 const Eigen::Quaterniond& q_W_B_measured,
                                                 const SE3d& T_B_C, NoiseModel noise,
                                                 RobustLoss robust_loss)
    : CeresFactor(activeControlPointKeys(spline.segmentAt(t_fix)), std::move(noise), robust_loss),
      t_fix_(t_fix),
      segment_(spline.segmentAt(t_fix)),
      q_W_B_measured_(requireUnitQuaternion("SplineInsAttitudeFactor", "measured attitude q_W_B",
                                            q_W_B_measured)),
      T_B_C_(requireRigidTransform("SplineInsAttitudeFactor", "T_B_C", T_B_C)) {
  requireNoiseDimension("SplineInsAttitudeFactor", this->noise(), kResidualDimension);
}

std::unique_ptr<ceres::CostFunction> SplineInsAttitudeFactor::createCostFunction() const {
  return std::make_unique<
      ceres::AutoDiffCostFunction<SplineInsAttitudeResidual, kResidualDimension, P, P, P, P>>(
      new SplineInsAttitudeResidual{segment_.u, q_W_B_measured_.conjugate(), T_B_C_.q.conjugate()});
}

}  // namespace hsmap
