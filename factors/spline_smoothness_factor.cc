#include "factors/spline_smoothness_factor.h"

#include <ceres/autodiff_cost_function.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "factors/factor_argument_checks.h"

namespace hsmap {

namespace {

void requirePositive(const char* what, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    std::ostringstream message;
    message << "SplineSmoothnessFactor: " << what << " must be a positive finite number, got "
            << value;
    throw std::invalid_argument(message.str());
  }
}

Key previousControlPoint(std::uint64_t i) {
  if (i == 0) {
    throw std::invalid_argument(
        "SplineSmoothnessFactor: control point 0 has no predecessor (i must be >= 1)");
  }
  return S(i - 1);
}

}  // namespace

NoiseModel SplineSmoothnessFactor::noiseFromAccelerationSigmas(double sigma_linear_acceleration,
                                                               double sigma_angular_acceleration,
                                                               double dt) {
  requirePositive("sigma_linear_acceleration", sigma_linear_acceleration);
  requirePositive("sigma_angular_acceleration", sigma_angular_acceleration);
  requirePositive("dt", dt);
  const double dt2 = dt * dt;
  Eigen::VectorXd sigmas(kResidualDimension);
  sigmas << Eigen::Vector3d::Constant(sigma_linear_acceleration * dt2),
      Eigen::Vector3d::Constant(sigma_angular_acceleration * dt2);
  return NoiseModel::fromSigmas(sigmas);
}

SplineSmoothnessFactor::SplineSmoothnessFactor(std::uint64_t i, NoiseModel noise)
    : SplineSmoothnessFactor(previousControlPoint(i), S(i), S(i + 1), std::move(noise)) {}

SplineSmoothnessFactor::SplineSmoothnessFactor(Key previous, Key current, Key next,
                                               NoiseModel noise)
    : CeresFactor({previous, current, next}, std::move(noise), RobustLoss::none()) {
  requireNoiseDimension("SplineSmoothnessFactor", this->noise(), kResidualDimension);
}

std::unique_ptr<ceres::CostFunction> SplineSmoothnessFactor::createCostFunction() const {
  constexpr int P = SE3d::kNumParameters;
  return std::make_unique<
      ceres::AutoDiffCostFunction<SplineSmoothnessResidual, kResidualDimension, P, P, P>>(
      new SplineSmoothnessResidual{});
}

}  // namespace hsmap
