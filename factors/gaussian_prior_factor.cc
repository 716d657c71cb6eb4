#include "factors/gaussian_prior_factor.h"

#include <ceres/cost_function.h>

#include <stdexcept>

#include "factors/factor_argument_checks.h"

namespace hsmap {

namespace {

class PriorCost : public ceres::CostFunction {
 public:
  explicit PriorCost(Eigen::VectorXd prior) : prior_(std::move(prior)) {
    set_num_residuals(int(prior_.size()));
    mutable_parameter_block_sizes()->push_back(int(prior_.size()));
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Index n = prior_.size();
    for (Eigen::Index i = 0; i < n; ++i) residuals[i] = parameters[0][i] - prior_[i];
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(jacobians[0], n, n)
          .setIdentity();
    }
    return true;
  }

 private:
  Eigen::VectorXd prior_;
};

}  // namespace

GaussianPriorFactor::GaussianPriorFactor(Key variable, Eigen::VectorXd prior, NoiseModel noise)
    : CeresFactor({variable}, std::move(noise), RobustLoss::none()), prior_(std::move(prior)) {
  if (prior_.size() == 0) throw std::invalid_argument("GaussianPriorFactor: an empty prior");
  requireNoiseDimension("GaussianPriorFactor", this->noise(), int(prior_.size()));
  requireFinite("GaussianPriorFactor", "prior", prior_);
}

std::unique_ptr<ceres::CostFunction> GaussianPriorFactor::createCostFunction() const {
  return std::make_unique<PriorCost>(prior_);
}

}  // namespace hsmap
