#pragma once
// InsPositionFactor: the INS position fix of the body B, constraining the
// pose of the RGB camera through the known lever arm T_B_C.
//
//   variable   x = T_W_C (pose, [qx qy qz qw tx ty tz])
//   model      T_W_B = T_W_C * T_B_C^-1, so t_W_B = R_W_C t_C_B + t_W_C
//              with T_C_B = T_B_C^-1
//   residual   r = t_W_B - p_W_B_measured                  (3, metres, in W)
// W is the local North-East-Down frame (DATASET.md), so the residual's
// components are north, east, down: a noise model from the survey's sigmas is
// fromSigmas([sigma_horizontal, sigma_horizontal, sigma_depth]).
// The fix must already be in W (geodetic -> NED is core/geometry's job) and
// at the time of the pose (interpolated by the caller).

#include <Eigen/Core>
#include <memory>
#include <string>

#include "core/geometry/se3.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"

namespace hsmap {

// Ceres functor: (pose T_W_C [7]) -> residual [3].
struct InsPositionResidual {
  Eigen::Vector3d p_W_B_measured;
  Eigen::Vector3d t_C_B;  // translation of T_C_B = T_B_C^-1 (origin of B in C)

  template <class T>
  bool operator()(const T* pose_T_W_C, T* residual) const {
    const SE3<T> T_W_C = SE3<T>::fromParameters(pose_T_W_C);
    const Vector3<T> t_W_B = T_W_C * Vector3<T>(t_C_B.cast<T>());
    for (int i = 0; i < 3; ++i) residual[i] = t_W_B[i] - p_W_B_measured[i];
    return true;
  }
};

class InsPositionFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 3;

  // Throws std::invalid_argument for a noise model that is not 3-dimensional,
  // a non-finite fix or a T_B_C whose rotation is not a unit quaternion.
  InsPositionFactor(Key pose_T_W_C, const Eigen::Vector3d& p_W_B_measured, const SE3d& T_B_C,
                    NoiseModel noise, RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "InsPositionFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const Eigen::Vector3d& measuredPosition() const { return p_W_B_measured_; }
  const SE3d& T_B_C() const { return T_B_C_; }

 private:
  Eigen::Vector3d p_W_B_measured_;
  SE3d T_B_C_;
};

}  // namespace hsmap
