#pragma once
// Small factors used only by the solver tests, so that the solver can be
// checked on problems whose answer is known in closed form:
//   LinearFactor        r = sum_k A_k x_k - b   (linear-Gaussian problems)
//   TestPosePriorFactor r = log(prior^-1 T)     (6, [rho; phi], autodiff)
//   TestBetweenFactor   r = log(T_a_b^-1 T_a^-1 T_b)
//   NotACeresFactor     a Factor the Ceres solver cannot evaluate

#include <ceres/autodiff_cost_function.h>
#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/se3.h"
#include "core/graph/factor.h"
#include "factors/ceres_factor.h"

namespace hsmap::test {

class LinearCostFunction final : public ceres::CostFunction {
 public:
  LinearCostFunction(std::vector<Eigen::MatrixXd> A, Eigen::VectorXd b)
      : A_(std::move(A)), b_(std::move(b)) {
    set_num_residuals(static_cast<int>(b_.size()));
    for (const Eigen::MatrixXd& A_k : A_) {
      mutable_parameter_block_sizes()->push_back(static_cast<int32_t>(A_k.cols()));
    }
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    Eigen::Map<Eigen::VectorXd> r(residuals, b_.size());
    r = -b_;
    for (std::size_t k = 0; k < A_.size(); ++k) {
      r += A_[k] * Eigen::Map<const Eigen::VectorXd>(parameters[k], A_[k].cols());
      if (jacobians != nullptr && jacobians[k] != nullptr) {
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            jacobians[k], A_[k].rows(), A_[k].cols()) = A_[k];
      }
    }
    return true;
  }

 private:
  std::vector<Eigen::MatrixXd> A_;
  Eigen::VectorXd b_;
};

class LinearFactor final : public CeresFactor {
 public:
  LinearFactor(std::vector<Key> keys, std::vector<Eigen::MatrixXd> A, Eigen::VectorXd b,
               NoiseModel noise, RobustLoss loss = RobustLoss::none())
      : CeresFactor(std::move(keys), std::move(noise), loss), A_(std::move(A)), b_(std::move(b)) {}
  std::string name() const override { return "LinearFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override {
    return std::make_unique<LinearCostFunction>(A_, b_);
  }
  const std::vector<Eigen::MatrixXd>& A() const { return A_; }
  const Eigen::VectorXd& b() const { return b_; }

 private:
  std::vector<Eigen::MatrixXd> A_;
  Eigen::VectorXd b_;
};

struct PosePriorResidual {
  SE3d prior_inverse;
  template <class T>
  bool operator()(const T* pose, T* residual) const {
    const SE3<T> T_pose = SE3<T>::fromParameters(pose);
    Eigen::Map<Vector6<T>> r(residual);
    r = (prior_inverse.cast<T>() * T_pose).log();
    return true;
  }
};

class TestPosePriorFactor final : public CeresFactor {
 public:
  TestPosePriorFactor(Key key, const SE3d& prior, NoiseModel noise,
                      RobustLoss loss = RobustLoss::none())
      : CeresFactor({key}, std::move(noise), loss), prior_(prior) {}
  std::string name() const override { return "TestPosePriorFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override {
    return std::make_unique<ceres::AutoDiffCostFunction<PosePriorResidual, 6, 7>>(
        new PosePriorResidual{prior_.inverse()});
  }

 private:
  SE3d prior_;
};

struct BetweenResidual {
  SE3d measured_inverse;
  template <class T>
  bool operator()(const T* a, const T* b, T* residual) const {
    const SE3<T> T_a = SE3<T>::fromParameters(a);
    const SE3<T> T_b = SE3<T>::fromParameters(b);
    Eigen::Map<Vector6<T>> r(residual);
    r = (measured_inverse.cast<T>() * T_a.inverse() * T_b).log();
    return true;
  }
};

class TestBetweenFactor final : public CeresFactor {
 public:
  TestBetweenFactor(Key a, Key b, const SE3d& T_a_b, NoiseModel noise)
      : CeresFactor({a, b}, std::move(noise), RobustLoss::none()), T_a_b_(T_a_b) {}
  std::string name() const override { return "TestBetweenFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override {
    return std::make_unique<ceres::AutoDiffCostFunction<BetweenResidual, 6, 7, 7>>(
        new BetweenResidual{T_a_b_.inverse()});
  }

 private:
  SE3d T_a_b_;
};

class NotACeresFactor final : public Factor {
 public:
  explicit NotACeresFactor(Key key) : Factor({key}, NoiseModel::isotropic(1, 1.0), RobustLoss::none()) {}
  std::string name() const override { return "NotACeresFactor"; }
};

// A random rotation + translation of moderate size (deterministic given the
// generator).
template <class Rng>
SE3d randomPose(Rng& rng, double translation_scale = 1.0) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector3d phi(normal(rng), normal(rng), normal(rng));
  Eigen::Vector3d t(normal(rng), normal(rng), normal(rng));
  return SE3d(expSO3(phi), translation_scale * t);
}

}  // namespace hsmap::test
