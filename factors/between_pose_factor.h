#pragma once
// BetweenPoseFactor: a measured relative pose between two pose variables
// (odometry, a loop closure, a relative pose from local bundle adjustment).
//
//   variables  a = T_W_A, b = T_W_B (poses, [qx qy qz qw tx ty tz])
//   residual   r = log(T_A_B_measured^-1 * T_W_A^-1 * T_W_B) = [rho; phi]   (6)
// rho in metres and phi in radians (se3.h's log, translation first),
// expressed in B: T_A_B(predicted) = T_A_B_measured * exp(r).

#include <memory>
#include <string>

#include "core/geometry/se3.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"

namespace hsmap {

// Ceres functor: (pose T_W_A [7], pose T_W_B [7]) -> residual [6].
struct BetweenPoseResidual {
  SE3d T_B_A_measured;  // T_A_B_measured^-1

  template <class T>
  bool operator()(const T* pose_T_W_A, const T* pose_T_W_B, T* residual) const {
    const SE3<T> T_A_B = SE3<T>::fromParameters(pose_T_W_A).inverse() *
                         SE3<T>::fromParameters(pose_T_W_B);
    const Vector6<T> r = (T_B_A_measured.cast<T>() * T_A_B).log();
    for (int i = 0; i < 6; ++i) residual[i] = r[i];
    return true;
  }
};

class BetweenPoseFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 6;

  // Throws std::invalid_argument for a noise model that is not 6-dimensional
  // or a measurement whose rotation is not a unit quaternion.
  BetweenPoseFactor(Key pose_T_W_A, Key pose_T_W_B, const SE3d& T_A_B_measured, NoiseModel noise,
                    RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "BetweenPoseFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const SE3d& measured() const { return T_A_B_measured_; }

 private:
  SE3d T_A_B_measured_;
};

}  // namespace hsmap
