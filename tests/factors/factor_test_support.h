#pragma once
// Helpers for the factor tests: parameter blocks in the layouts of
// core/graph/values.h, evaluation through ceres::CostFunction::Evaluate, and
// the check of a factor's Jacobians in the TANGENT space the solver uses.
//
// Tangent space: a pose block [qx qy qz qw tx ty tz] is perturbed on the
// right, T (+) xi = T * exp(xi) with xi = [rho; phi] (se3.h), as by the
// solver's SE(3) manifold; points, scalars and vectors are perturbed by
// plain addition. Ceres' Jacobians are with respect to the ambient block
// (7 columns for a pose), so the tangent Jacobian is J_ambient * P with P the
// Jacobian of the block's parameters with respect to xi at xi = 0 (7x6):
//   d q / d phi = q (x) [0, phi/2]:  d[qx qy qz]/d phi = (qw I + hat(q_vec)) / 2,
//                                    d qw / d phi = -q_vec^T / 2
//   d t / d rho = R,  d t / d phi = 0,  d q / d rho = 0.
// The numeric reference is the fourth-order central difference
//   (r(-2h) - 8 r(-h) + 8 r(h) - r(2h)) / (12 h),   h = 1e-4,
// of the residual under T * exp(h e_k). Its truncation error is O(h^4) (below
// 1e-13 here) and its rounding error ~1.5 eps_r / h, where eps_r ~ 1e-12 px
// is the rounding of a residual computed through world positions of tens of
// metres and f / z ~ 500 px/m: about 1e-8, where the plain two-point
// difference at h = 1e-6 would give 1e-6. The comparison tolerance is 1e-6
// relative to the block's largest entry (absolute for blocks whose entries
// are all below 1), so a block with weak influence (a spline control point
// barely active at the time) is held to the same absolute accuracy.

#include <ceres/cost_function.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <random>
#include <sstream>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/se3.h"
#include "core/geometry/so3.h"

namespace hsmap::test {

enum class BlockKind { pose, euclidean };

struct ParameterBlock {
  BlockKind kind = BlockKind::euclidean;
  std::vector<double> values;

  int ambientSize() const { return static_cast<int>(values.size()); }
  int tangentSize() const { return kind == BlockKind::pose ? 6 : ambientSize(); }
};

inline ParameterBlock poseBlock(const SE3d& T) {
  ParameterBlock block{BlockKind::pose, std::vector<double>(SE3d::kNumParameters)};
  T.toParameters(block.values.data());
  return block;
}

inline ParameterBlock vectorBlock(const Eigen::VectorXd& v) {
  return {BlockKind::euclidean, std::vector<double>(v.data(), v.data() + v.size())};
}

inline ParameterBlock scalarBlock(double x) { return {BlockKind::euclidean, {x}}; }

// block (+) delta in the tangent space (see the header comment).
inline ParameterBlock plus(const ParameterBlock& block, const Eigen::VectorXd& delta) {
  ParameterBlock out = block;
  if (block.kind == BlockKind::pose) {
    const SE3d T = SE3d::fromParameters(block.values.data()) * SE3d::exp(Vector6d(delta));
    T.toParameters(out.values.data());
  } else {
    for (int i = 0; i < block.ambientSize(); ++i) out.values[i] += delta[i];
  }
  return out;
}

// d block(+)delta / d delta at delta = 0 (ambient x tangent).
inline Eigen::MatrixXd plusJacobian(const ParameterBlock& block) {
  if (block.kind == BlockKind::euclidean) {
    return Eigen::MatrixXd::Identity(block.ambientSize(), block.ambientSize());
  }
  const SE3d T = SE3d::fromParameters(block.values.data());
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(7, 6);
  P.block<3, 3>(0, 3) = 0.5 * (T.q.w() * Eigen::Matrix3d::Identity() + hat(T.q.vec()));
  P.block<1, 3>(3, 3) = -0.5 * T.q.vec().transpose();
  P.block<3, 3>(4, 0) = T.rotationMatrix();
  return P;
}

struct Evaluation {
  bool ok = false;
  Eigen::VectorXd residual;
  std::vector<Eigen::MatrixXd> jacobians;  // ambient: num_residuals x block size
};

inline Evaluation evaluate(const ceres::CostFunction& cost, const std::vector<ParameterBlock>& blocks,
                           bool with_jacobians = true) {
  Evaluation out;
  std::vector<const double*> parameters;
  for (const ParameterBlock& block : blocks) parameters.push_back(block.values.data());
  const int m = cost.num_residuals();
  out.residual.resize(m);
  std::vector<std::vector<double>> storage;
  std::vector<double*> jacobians;
  for (const ParameterBlock& block : blocks) {
    storage.emplace_back(static_cast<std::size_t>(m * block.ambientSize()));
  }
  for (auto& s : storage) jacobians.push_back(s.data());
  out.ok = cost.Evaluate(parameters.data(), out.residual.data(),
                         with_jacobians ? jacobians.data() : nullptr);
  if (with_jacobians) {
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      out.jacobians.push_back(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic,
                                                              Eigen::RowMajor>>(
          storage[b].data(), m, blocks[b].ambientSize()));
    }
  }
  return out;
}

inline Eigen::VectorXd residualAt(const ceres::CostFunction& cost,
                                  const std::vector<ParameterBlock>& blocks) {
  return evaluate(cost, blocks, false).residual;
}

// Fourth-order central-difference Jacobians in the tangent space, one per block.
inline std::vector<Eigen::MatrixXd> numericTangentJacobians(const ceres::CostFunction& cost,
                                                            const std::vector<ParameterBlock>& blocks,
                                                            double h = 1e-4) {
  std::vector<Eigen::MatrixXd> out;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    Eigen::MatrixXd J(cost.num_residuals(), blocks[b].tangentSize());
    for (int k = 0; k < blocks[b].tangentSize(); ++k) {
      const Eigen::VectorXd step = h * Eigen::VectorXd::Unit(blocks[b].tangentSize(), k);
      const auto residualWithStep = [&](double multiple) {
        std::vector<ParameterBlock> moved = blocks;
        moved[b] = plus(blocks[b], multiple * step);
        return residualAt(cost, moved);
      };
      J.col(k) = (residualWithStep(-2.0) - 8.0 * residualWithStep(-1.0) +
                  8.0 * residualWithStep(1.0) - residualWithStep(2.0)) /
                 (12.0 * h);
    }
    out.push_back(J);
  }
  return out;
}

// The block sizes of the cost function match `blocks`, evaluation succeeds,
// residual and Jacobians are finite, and every J_ambient * P matches the
// numeric tangent Jacobian to `tolerance` relative to its largest entry.
inline ::testing::AssertionResult tangentJacobiansMatchNumeric(
    const ceres::CostFunction& cost, const std::vector<ParameterBlock>& blocks,
    double tolerance = 1e-6) {
  const std::vector<int32_t>& sizes = cost.parameter_block_sizes();
  if (sizes.size() != blocks.size()) {
    return ::testing::AssertionFailure() << "cost function has " << sizes.size()
                                         << " parameter blocks, the state " << blocks.size();
  }
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (sizes[b] != blocks[b].ambientSize()) {
      return ::testing::AssertionFailure() << "block " << b << " has size " << sizes[b]
                                           << " in the cost function, " << blocks[b].ambientSize()
                                           << " in the state";
    }
  }
  const Evaluation evaluation = evaluate(cost, blocks);
  if (!evaluation.ok) return ::testing::AssertionFailure() << "Evaluate() returned false";
  if (!evaluation.residual.allFinite()) {
    return ::testing::AssertionFailure() << "residual not finite: " << evaluation.residual.transpose();
  }
  const std::vector<Eigen::MatrixXd> numeric = numericTangentJacobians(cost, blocks);
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const Eigen::MatrixXd analytic = evaluation.jacobians[b] * plusJacobian(blocks[b]);
    if (!analytic.allFinite()) {
      return ::testing::AssertionFailure() << "Jacobian of block " << b << " not finite";
    }
    const double scale = std::max(1.0, numeric[b].cwiseAbs().maxCoeff());
    const double error = (analytic - numeric[b]).cwiseAbs().maxCoeff();
    if (error > tolerance * scale) {
      std::ostringstream message;
      message << "block " << b << ": max |J - J_numeric| = " << error << " > " << tolerance
              << " * " << scale << "\nJ (tangent) =\n"
              << analytic << "\nJ_numeric =\n"
              << numeric[b];
      return ::testing::AssertionFailure() << message.str();
    }
  }
  return ::testing::AssertionSuccess();
}

// A pose with a rotation of up to ~max_angle radians about a random axis and
// a translation with components in [-max_translation, max_translation].
inline SE3d randomPose(std::mt19937& rng, double max_angle, double max_translation) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::Vector3d omega(unit(rng), unit(rng), unit(rng));
  const Eigen::Vector3d t(unit(rng), unit(rng), unit(rng));
  return SE3d(expSO3(Eigen::Vector3d(omega * (max_angle / std::sqrt(3.0)))), t * max_translation);
}

inline Eigen::Vector3d randomVector(std::mt19937& rng, const Eigen::Vector3d& low,
                                    const Eigen::Vector3d& high) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = std::uniform_real_distribution<double>(low[i], high[i])(rng);
  return v;
}

// The undistorted 960x540 pinhole camera the reprojection tests share
// (fx != fy, so a swapped axis shows).
inline PinholeRadtanParameters pinholeTestCamera() {
  PinholeRadtanParameters p;
  p.width = 960;
  p.height = 540;
  p.fx = 800.0;
  p.fy = 700.0;
  p.cx = 480.0;
  p.cy = 270.0;
  return p;
}

}  // namespace hsmap::test
