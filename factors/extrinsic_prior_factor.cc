#include "factors/extrinsic_prior_factor.h"

#include <ceres/autodiff_cost_function.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "factors/factor_argument_checks.h"

namespace hsmap {

namespace {

void requirePositive(const char* what, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    std::ostringstream message;
    message << "ExtrinsicPriorFactor: " << what << " must be a positive finite number, got "
            << value;
    throw std::invalid_argument(message.str());
  }
}

}  // namespace

NoiseModel ExtrinsicPriorFactor::noiseFromSigmas(double sigma_rotation_deg,
                                                 double sigma_translation_m) {
  requirePositive("sigma_rotation_deg", sigma_rotation_deg);
  requirePositive("sigma_translation_m", sigma_translation_m);
  const double sigma_rotation_rad = sigma_rotation_deg * (std::numbers::pi / 180.0);
  Eigen::VectorXd sigmas(kResidualDimension);
  sigmas << sigma_translation_m, sigma_translation_m, sigma_translation_m, sigma_rotation_rad,
      sigma_rotation_rad, sigma_rotation_rad;
  return NoiseModel::fromSigmas(sigmas);
}

ExtrinsicPriorFactor::ExtrinsicPriorFactor(Key extrinsic_T_C_U, const SE3d& T_C_U_prior,
                                           NoiseModel noise)
    : CeresFactor({extrinsic_T_C_U}, std::move(noise), RobustLoss::none()),
      T_C_U_prior_(requireRigidTransform("ExtrinsicPriorFactor", "prior T_C_U", T_C_U_prior)) {
  requireNoiseDimension("ExtrinsicPriorFactor", this->noise(), kResidualDimension);
}

std::unique_ptr<ceres::CostFunction> ExtrinsicPriorFactor::createCostFunction() const {
  return std::make_unique<ceres::AutoDiffCostFunction<ExtrinsicPriorResidual, kResidualDimension,
                                                      SE3d::kNumParameters>>(
      new ExtrinsicPriorResidual{T_C_U_prior_});
}

}  // namespace hsmap
