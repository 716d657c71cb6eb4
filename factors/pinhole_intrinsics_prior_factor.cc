#include "factors/pinhole_intrinsics_prior_factor.h"

#include <ceres/cost_function.h>

#include <cmath>
#include <stdexcept>

#include "factors/factor_argument_checks.h"

namespace hsmap {

namespace {

constexpr const char* kName = "PinholeIntrinsicsPriorFactor";
constexpr int kSize = PinholeRadtanCamera::kNumIntrinsics;

std::vector<int> freeOf(const PinholeIntrinsicsPriorFactor::Intrinsics& sigmas) {
  std::vector<int> free;
  for (int i = 0; i < kSize; ++i) {
    if (!(sigmas[std::size_t(i)] >= 0.0) || !std::isfinite(sigmas[std::size_t(i)])) {
      throw std::invalid_argument(std::string(kName) + ": sigma of parameter " + std::to_string(i) +
                                  " must be finite and >= 0, got " +
                                  std::to_string(sigmas[std::size_t(i)]));
    }
    if (sigmas[std::size_t(i)] > 0.0) free.push_back(i);
  }
  if (free.empty()) {
    throw std::invalid_argument(std::string(kName) +
                                ": every sigma is 0, nothing to estimate (hold the block constant instead)");
  }
  return free;
}

NoiseModel noiseOf(const PinholeIntrinsicsPriorFactor::Intrinsics& sigmas) {
  const std::vector<int> free = freeOf(sigmas);
  Eigen::VectorXd s(Eigen::Index(free.size()));
  for (std::size_t i = 0; i < free.size(); ++i) s[Eigen::Index(i)] = sigmas[std::size_t(free[i])];
  return NoiseModel::fromSigmas(s);
}

// r = k[free] - prior[free]; J = the identity's rows of the free parameters.
class SelectedDifference : public ceres::CostFunction {
 public:
  SelectedDifference(const PinholeIntrinsicsPriorFactor::Intrinsics& prior, std::vector<int> free)
      : prior_(prior), free_(std::move(free)) {
    set_num_residuals(int(free_.size()));
    mutable_parameter_block_sizes()->push_back(kSize);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* k = parameters[0];
    for (std::size_t i = 0; i < free_.size(); ++i) {
      residuals[i] = k[free_[i]] - prior_[std::size_t(free_[i])];
    }
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      for (std::size_t i = 0; i < free_.size(); ++i) {
        for (int c = 0; c < kSize; ++c) jacobians[0][i * kSize + std::size_t(c)] = c == free_[i] ? 1.0 : 0.0;
      }
    }
    return true;
  }

 private:
  PinholeIntrinsicsPriorFactor::Intrinsics prior_;
  std::vector<int> free_;
};

}  // namespace

PinholeIntrinsicsPriorFactor::PinholeIntrinsicsPriorFactor(Key rgb_intrinsics, const Intrinsics& prior,
                                                               const Intrinsics& sigmas)
    : CeresFactor({rgb_intrinsics}, noiseOf(sigmas), RobustLoss::none()),
      prior_(prior),
      free_(freeOf(sigmas)) {
  for (double value : prior_) requireFinite(kName, "prior intrinsics", value);
}

std::vector<int> PinholeIntrinsicsPriorFactor::heldParameters(const Intrinsics& sigmas) {
  std::vector<int> held;
  for (int i = 0; i < kSize; ++i) {
    if (!(sigmas[std::size_t(i)] > 0.0)) held.push_back(i);
  }
  return held;
}

std::unique_ptr<ceres::CostFunction> PinholeIntrinsicsPriorFactor::createCostFunction() const {
  return std::make_unique<SelectedDifference>(prior_, free_);
}

}  // namespace hsmap
