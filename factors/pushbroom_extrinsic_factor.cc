#include "factors/pushbroom_extrinsic_factor.h"

#include <ceres/autodiff_cost_function.h>

#include "factors/factor_argument_checks.h"

namespace hsmap {

namespace {
constexpr const char* kName = "PushbroomExtrinsicFactor";
}  // namespace

PushbroomExtrinsicFactor::PushbroomExtrinsicFactor(Key extrinsic_T_C_U, const SE3d& T_W_C,
                                                   const Eigen::Vector3d& p_W, double u_measured,
                                                   const PushbroomParameters& camera,
                                                   NoiseModel noise, RobustLoss robust_loss)
    : CeresFactor({extrinsic_T_C_U}, std::move(noise), robust_loss),
      T_W_C_(requireRigidTransform(kName, "line pose T_W_C", T_W_C)),
      p_W_(p_W),
      u_measured_(u_measured),
      camera_(camera) {
  requireNoiseDimension(kName, this->noise(), kResidualDimension);
  requireFinite(kName, "point p_W", p_W);
  requireFinite(kName, "sample u", u_measured);
}

std::unique_ptr<ceres::CostFunction> PushbroomExtrinsicFactor::createCostFunction() const {
  return std::make_unique<ceres::AutoDiffCostFunction<PushbroomExtrinsicResidual,
                                                      kResidualDimension, SE3d::kNumParameters>>(
      new PushbroomExtrinsicResidual{T_W_C_, p_W_, u_measured_, camera_.intrinsics()});
}

}  // namespace hsmap
