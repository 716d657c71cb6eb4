#pragma once
// ReprojectionWithIntrinsicsFactor: ReprojectionFactor's measurement
// (reprojection_factor.h) with the RGB camera's intrinsics estimated too.
//
//   variables  x = T_W_C (pose), l = p_W (point, m),
//              k = K(i) (vector of 9: [fx fy cx cy k1 k2 p1 p2 k3], pixels and
//                  unitless distortion coefficients, OpenCV's order)
//   residual   r = project_k(T_W_C^-1 p_W) - pixel        (2, pixels)
// Same frames, pixel convention and behind-camera treatment (soft depth
// floor, positive_depth.h) as ReprojectionFactor. The image size is not a
// variable and not needed by the residual.

#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"
#include "factors/world_point_projection.h"

namespace hsmap {

// Ceres functor: (pose T_W_C [7], landmark p_W [3], intrinsics [9]) -> residual [2].
struct ReprojectionWithIntrinsicsResidual {
  Eigen::Vector2d pixel;

  template <class T>
  bool operator()(const T* pose_T_W_C, const T* landmark_p_W, const T* intrinsics,
                  T* residual) const {
    const Vector2<T> predicted =
        projectPinhole(SE3<T>::fromParameters(pose_T_W_C),
                       Vector3<T>(landmark_p_W[0], landmark_p_W[1], landmark_p_W[2]), intrinsics);
    residual[0] = predicted.x() - pixel.x();
    residual[1] = predicted.y() - pixel.y();
    return true;
  }
};

class ReprojectionWithIntrinsicsFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 2;

  // Throws std::invalid_argument for a noise model that is not 2-dimensional
  // or a non-finite pixel.
  ReprojectionWithIntrinsicsFactor(Key pose_T_W_C, Key landmark_p_W, Key intrinsics,
                                   const Eigen::Vector2d& pixel, NoiseModel noise,
                                   RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "ReprojectionWithIntrinsicsFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const Eigen::Vector2d& pixel() const { return pixel_; }

 private:
  Eigen::Vector2d pixel_;
};

}  // namespace hsmap
