#pragma once
// Comparison of a factor's cost function with a reference implementation of
// the same residual (e.g. analytic Jacobians against the autodiff functor),
// in the solver's tangent space (factor_test_support.h): ambient Jacobians
// may differ (an analytic factor returns J_tangent * MinusJacobian, autodiff
// the raw derivative), J_ambient * PlusJacobian must not.

#include <ceres/cost_function.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <vector>

#include "tests/factors/factor_test_support.h"

namespace hsmap::test {

// Residuals equal to `residual_tolerance` (relative to max(1, |r|)) and every
// tangent Jacobian block equal to `jacobian_tolerance` relative to the
// reference block's largest entry (absolute below 1). Also: the cost's
// residual-only evaluation gives exactly the residual of its evaluation with
// Jacobians (Ceres mixes both in one solve).
inline ::testing::AssertionResult tangentJacobiansMatchReference(
    const ceres::CostFunction& cost, const ceres::CostFunction& reference,
    const std::vector<ParameterBlock>& blocks, double jacobian_tolerance = 1e-9,
    double residual_tolerance = 1e-12) {
  if (cost.parameter_block_sizes() != reference.parameter_block_sizes() ||
      cost.num_residuals() != reference.num_residuals()) {
    return ::testing::AssertionFailure() << "the cost functions have different shapes";
  }
  const Evaluation evaluation = evaluate(cost, blocks);
  const Evaluation expected = evaluate(reference, blocks);
  if (!evaluation.ok || !expected.ok) {
    return ::testing::AssertionFailure() << "Evaluate() returned false";
  }
  const Eigen::VectorXd residual_only = evaluate(cost, blocks, false).residual;
  if (residual_only != evaluation.residual) {
    return ::testing::AssertionFailure()
           << "residual only " << residual_only.transpose() << " != residual with Jacobians "
           << evaluation.residual.transpose();
  }
  const double residual_error = (evaluation.residual - expected.residual).cwiseAbs().maxCoeff();
  const double residual_scale = std::max(1.0, expected.residual.cwiseAbs().maxCoeff());
  if (!(residual_error <= residual_tolerance * residual_scale)) {
    return ::testing::AssertionFailure()
           << "residual " << evaluation.residual.transpose() << " != reference "
           << expected.residual.transpose();
  }
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const Eigen::MatrixXd P = plusJacobian(blocks[b]);
    const Eigen::MatrixXd J = evaluation.jacobians[b] * P;
    const Eigen::MatrixXd J_reference = expected.jacobians[b] * P;
    const double scale = std::max(1.0, J_reference.cwiseAbs().maxCoeff());
    const double error = (J - J_reference).cwiseAbs().maxCoeff();
    if (!(error <= jacobian_tolerance * scale)) {
      std::ostringstream message;
      message << "block " << b << ": max |J - J_reference| = " << error << " > "
              << jacobian_tolerance << " * " << scale << "\nJ (tangent) =\n"
              << J << "\nJ_reference =\n"
              << J_reference;
      return ::testing::AssertionFailure() << message.str();
    }
  }
  return ::testing::AssertionSuccess();
}

// Evaluate() with the Jacobians of only the blocks flagged in `wanted` (the
// others null, as Ceres asks for constant blocks) gives the same Jacobians
// for those blocks as a full evaluation.
inline ::testing::AssertionResult partialJacobiansMatchFull(
    const ceres::CostFunction& cost, const std::vector<ParameterBlock>& blocks,
    const std::vector<bool>& wanted) {
  const Evaluation full = evaluate(cost, blocks);
  std::vector<const double*> parameters;
  for (const ParameterBlock& block : blocks) parameters.push_back(block.values.data());
  const int m = cost.num_residuals();
  std::vector<std::vector<double>> storage;
  std::vector<double*> jacobians;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    storage.emplace_back(static_cast<std::size_t>(m * blocks[b].ambientSize()), -7.0);
    jacobians.push_back(wanted[b] ? storage.back().data() : nullptr);
  }
  Eigen::VectorXd residual(m);
  if (!cost.Evaluate(parameters.data(), residual.data(), jacobians.data())) {
    return ::testing::AssertionFailure() << "Evaluate() returned false";
  }
  if (residual != full.residual) return ::testing::AssertionFailure() << "residual differs";
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (!wanted[b]) continue;
    const Eigen::MatrixXd J = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic,
                                                              Eigen::RowMajor>>(
        storage[b].data(), m, blocks[b].ambientSize());
    if (J != full.jacobians[b]) {
      return ::testing::AssertionFailure() << "Jacobian of block " << b << " differs:\n"
                                           << J << "\nfull:\n"
                                           << full.jacobians[b];
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace hsmap::test
