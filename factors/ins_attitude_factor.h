#pragma once
// InsAttitudeFactor: the INS attitude of the body B, constraining the
// rotation of the RGB camera through the known mounting rotation q_B_C.
//
//   variable   x = T_W_C (pose; only its rotation q_W_C enters)
//   model      q_W_B = q_W_C * q_B_C^-1
//   residual   r = log(q_W_B_measured^-1 * q_W_C * q_B_C^-1)   (3, radians)
// r is the rotation vector of the error expressed in B (right perturbation:
// q_W_B = q_W_B_measured * exp(r)), so its components are about the body's
// x (forward, ~roll), y (starboard, ~pitch) and z (down, ~heading) axes for
// small pitch and roll. A noise model from the survey's
// sigma_attitude_deg = [roll, pitch, heading] is fromSigmas(those * pi/180).
// The measured attitude must be q_W_B (body to NED), e.g. from
// quaternionFromRollPitchHeadingDeg() in core/geometry/so3.h.

#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "core/geometry/se3.h"
#include "core/geometry/so3.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"

namespace hsmap {

// Ceres functor: (pose T_W_C [7]) -> residual [3].
struct InsAttitudeResidual {
  Eigen::Quaterniond q_B_W_measured;  // q_W_B_measured^-1
  Eigen::Quaterniond q_C_B;           // q_B_C^-1

  template <class T>
  bool operator()(const T* pose_T_W_C, T* residual) const {
    const Eigen::Quaternion<T> q_W_C(pose_T_W_C[3], pose_T_W_C[0], pose_T_W_C[1], pose_T_W_C[2]);
    const Eigen::Quaternion<T> error =
        q_B_W_measured.cast<T>() * q_W_C * q_C_B.cast<T>();
    const Vector3<T> r = logSO3(error);
    for (int i = 0; i < 3; ++i) residual[i] = r[i];
    return true;
  }
};

class InsAttitudeFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 3;

  // Throws std::invalid_argument for a noise model that is not 3-dimensional
  // or a measured attitude / T_B_C rotation that is not a unit quaternion.
  InsAttitudeFactor(Key pose_T_W_C, const Eigen::Quaterniond& q_W_B_measured, const SE3d& T_B_C,
                    NoiseModel noise, RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "InsAttitudeFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const Eigen::Quaterniond& measuredAttitude() const { return q_W_B_measured_; }
  const SE3d& T_B_C() const { return T_B_C_; }

 private:
  Eigen::Quaterniond q_W_B_measured_;
  SE3d T_B_C_;
};

}  // namespace hsmap
