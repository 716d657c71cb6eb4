#include "factors/parameter_subset_prior_factor.h"

#include <ceres/cost_function.h>

#include <cmath>
#include <stdexcept>
#include <utility>

#include "factors/factor_argument_checks.h"

namespace hsmap {

namespace {

std::vector<int> freeOf(const std::string& name, const std::vector<double>& sigmas) {
  std::vector<int> free;
  for (std::size_t i = 0; i < sigmas.size(); ++i) {
    if (!(sigmas[i] >= 0.0) || !std::isfinite(sigmas[i])) {
      throw std::invalid_argument(name + ": sigma of parameter " + std::to_string(i) +
                                  " must be finite and >= 0, got " + std::to_string(sigmas[i]));
    }
    if (sigmas[i] > 0.0) free.push_back(int(i));
  }
  if (free.empty()) {
    throw std::invalid_argument(name + ": every sigma is 0, nothing to estimate (hold the block constant instead)");
  }
  return free;
}

NoiseModel noiseOf(const std::string& name, const std::vector<double>& sigmas) {
  const std::vector<int> free = freeOf(name, sigmas);
  Eigen::VectorXd s(Eigen::Index(free.size()));
  for (std::size_t i = 0; i < free.size(); ++i) s[Eigen::Index(i)] = sigmas[std::size_t(free[i])];
  return NoiseModel::fromSigmas(s);
}

// r = k[free] - prior[free]; J = the identity's rows of the free components.
class SelectedDifference : public ceres::CostFunction {
 public:
  SelectedDifference(std::vector<double> prior, std::vector<int> free)
      : prior_(std::move(prior)), free_(std::move(free)) {
    set_num_residuals(int(free_.size()));
    mutable_parameter_block_sizes()->push_back(int(prior_.size()));
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* k = parameters[0];
    const std::size_t size = prior_.size();
    for (std::size_t i = 0; i < free_.size(); ++i) {
      residuals[i] = k[free_[i]] - prior_[std::size_t(free_[i])];
    }
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      for (std::size_t i = 0; i < free_.size(); ++i) {
        for (std::size_t c = 0; c < size; ++c) jacobians[0][i * size + c] = int(c) == free_[i] ? 1.0 : 0.0;
      }
    }
    return true;
  }

 private:
  std::vector<double> prior_;
  std::vector<int> free_;
};

}  // namespace

ParameterSubsetPriorFactor::ParameterSubsetPriorFactor(std::string name, Key block, std::vector<double> prior,
                                                       const std::vector<double>& sigmas)
    : CeresFactor({block}, noiseOf(name, sigmas), RobustLoss::none()),
      name_(std::move(name)),
      prior_(std::move(prior)),
      free_(freeOf(name_, sigmas)) {
  if (prior_.size() != sigmas.size()) {
    throw std::invalid_argument(name_ + ": " + std::to_string(prior_.size()) + " prior values but " +
                                std::to_string(sigmas.size()) + " sigmas");
  }
  for (double value : prior_) requireFinite(name_.c_str(), "prior intrinsics", value);
}

std::vector<int> ParameterSubsetPriorFactor::heldComponents(const std::vector<double>& sigmas) {
  std::vector<int> held;
  for (std::size_t i = 0; i < sigmas.size(); ++i) {
    if (!(sigmas[i] > 0.0)) held.push_back(int(i));
  }
  return held;
}

std::unique_ptr<ceres::CostFunction> ParameterSubsetPriorFactor::createCostFunction() const {
  return std::make_unique<SelectedDifference>(prior_, free_);
}

}  // namespace hsmap
