#pragma once
// ReprojectionFactor: a landmark seen at a pixel of an RGB keyframe, with the
// camera's intrinsics held fixed.
//
//   variables  x = T_W_C (pose, [qx qy qz qw tx ty tz]), l = p_W (point, m)
//   residual   r = project(T_W_C^-1 p_W) - pixel          (2, pixels)
// project() is the pinhole model with radial-tangential distortion of
// core/geometry/pinhole_radtan_camera.h; pixel centres at integer
// coordinates (OpenCV). The residual is raw: the solver whitens it with the
// noise model (typically isotropic, sigma ~ 1 px) and applies the robust loss
// (Huber or Cauchy, since feature tracks contain outliers).
//
// Behind the camera: the depth z_C goes through softPositiveDepth()
// (positive_depth.h): for z_C < 1 cm the division uses a positive floor that
// shrinks as the point moves behind the camera, so the residual stays finite
// and its gradient pushes the point in front again. The residual is unchanged
// for every point at least 1 cm in front of the camera.
//
// ReprojectionWithIntrinsicsFactor (reprojection_with_intrinsics_factor.h)
// is the same measurement with the intrinsics as a third variable.

#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"
#include "factors/world_point_projection.h"

namespace hsmap {

// Ceres functor: (pose T_W_C [7], landmark p_W [3]) -> residual [2].
struct ReprojectionResidual {
  Eigen::Vector2d pixel;
  std::array<double, PinholeRadtanCamera::kNumIntrinsics> intrinsics;

  template <class T>
  bool operator()(const T* pose_T_W_C, const T* landmark_p_W, T* residual) const {
    std::array<T, PinholeRadtanCamera::kNumIntrinsics> k;
    for (int i = 0; i < PinholeRadtanCamera::kNumIntrinsics; ++i) k[i] = T(intrinsics[i]);
    const Vector2<T> predicted =
        projectPinhole(SE3<T>::fromParameters(pose_T_W_C),
                       Vector3<T>(landmark_p_W[0], landmark_p_W[1], landmark_p_W[2]), k.data());
    residual[0] = predicted.x() - pixel.x();
    residual[1] = predicted.y() - pixel.y();
    return true;
  }
};

class ReprojectionFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 2;

  // Throws std::invalid_argument for a noise model that is not 2-dimensional,
  // a non-finite pixel or invalid intrinsics (PinholeRadtanCamera's checks).
  ReprojectionFactor(Key pose_T_W_C, Key landmark_p_W, const Eigen::Vector2d& pixel,
                     const PinholeRadtanParameters& intrinsics, NoiseModel noise,
                     RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "ReprojectionFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const Eigen::Vector2d& pixel() const { return pixel_; }
  // [fx fy cx cy k1 k2 p1 p2 k3]
  const std::array<double, PinholeRadtanCamera::kNumIntrinsics>& intrinsics() const {
    return intrinsics_;
  }

 private:
  Eigen::Vector2d pixel_;
  std::array<double, PinholeRadtanCamera::kNumIntrinsics> intrinsics_;
};

}  // namespace hsmap
