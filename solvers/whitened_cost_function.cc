#include "solvers/whitened_cost_function.h"

#include <stdexcept>
#include <string>

namespace hsmap {

namespace {
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
}  // namespace

WhitenedCostFunction::WhitenedCostFunction(std::unique_ptr<ceres::CostFunction> raw,
                                           const NoiseModel& noise)
    : raw_(std::move(raw)), diagonal_(noise.isDiagonal()) {
  if (!raw_) throw std::invalid_argument("WhitenedCostFunction: the raw cost function is null");
  if (raw_->num_residuals() != noise.dimension()) {
    throw std::invalid_argument("WhitenedCostFunction: the cost function returns " +
                                std::to_string(raw_->num_residuals()) +
                                " residuals but the noise model has dimension " +
                                std::to_string(noise.dimension()));
  }
  set_num_residuals(raw_->num_residuals());
  *mutable_parameter_block_sizes() = raw_->parameter_block_sizes();
  if (diagonal_) {
    diagonal_sqrt_information_ = noise.sqrtInformation().diagonal();
  } else {
    sqrt_information_ = noise.sqrtInformation();
  }
}

bool WhitenedCostFunction::Evaluate(double const* const* parameters, double* residuals,
                                    double** jacobians) const {
  if (!raw_->Evaluate(parameters, residuals, jacobians)) return false;
  const int m = num_residuals();
  const std::vector<int32_t>& block_sizes = parameter_block_sizes();
  Eigen::Map<Eigen::VectorXd> r(residuals, m);

  if (diagonal_) {
    r.array() *= diagonal_sqrt_information_.array();
    if (jacobians != nullptr) {
      for (std::size_t k = 0; k < block_sizes.size(); ++k) {
        if (jacobians[k] == nullptr) continue;
        Eigen::Map<RowMajorMatrix> J(jacobians[k], m, block_sizes[k]);
        J = diagonal_sqrt_information_.asDiagonal() * J;
      }
    }
    return true;
  }

  // General R: products into temporaries, as R * r would alias in place.
  const Eigen::VectorXd whitened = sqrt_information_ * r;
  r = whitened;
  if (jacobians != nullptr) {
    for (std::size_t k = 0; k < block_sizes.size(); ++k) {
      if (jacobians[k] == nullptr) continue;
      Eigen::Map<RowMajorMatrix> J(jacobians[k], m, block_sizes[k]);
      const RowMajorMatrix whitened_jacobian = sqrt_information_ * J;
      J = whitened_jacobian;
    }
  }
  return true;
}

}  // namespace hsmap
