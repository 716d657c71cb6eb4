#pragma once
// SplineReprojectionFactor: a landmark seen at a pixel of an RGB frame whose
// pose is not a variable of its own but the trajectory spline at the frame's
// time (continuous-time bundle adjustment).
//
//   variables  S(i), S(i+1), S(i+2), S(i+3): the four control points (poses
//              T_W_C, [qx qy qz qw tx ty tz]) active at the frame time t,
//              then l = p_W (point, m)
//   model      T_W_C(t) = spline(S(i..i+3), u) (core/geometry/se3_bspline.h),
//              i, u from SplineTiming::segmentAt(t), fixed at construction
//              (the RGB frame time is known exactly: no time offset here)
//   residual   r = project(T_W_C(t)^-1 p_W) - pixel        (2, pixels)
// The spline represents the RGB camera's pose T_W_C(t) directly. project() is
// the pinhole-radtan model with fixed intrinsics; depth floored as in
// ReprojectionFactor (positive_depth.h) so points behind the camera stay finite.
//
// Jacobians. createCostFunction() evaluates them analytically: the spline's
// control-point Jacobians (core/geometry/se3_bspline_jacobians.h) chained with
// the projection's (world_point_projection_jacobians.h): ~1.7 us per
// evaluation against ~30 us for autodiff through the spline with 31-derivative
// Jets (benchmarks/factors_bench.cc, docs/BENCHMARKS.md). The pose
// blocks' Jacobians are in the form of pose_block_jacobian.h: exact through
// the solver's Se3Manifold. createAutoDiffCostFunction() is the autodiff of
// SplineReprojectionResidual below, the reference the tests compare with.

#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"
#include "core/geometry/se3_bspline.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"
#include "factors/spline_timing.h"
#include "factors/world_point_projection.h"

namespace hsmap {

// Ceres functor: (control points S(i..i+3) [7 each], landmark p_W [3]) -> residual [2].
struct SplineReprojectionResidual {
  double u;  // normalised time of the frame in segment i
  Eigen::Vector2d pixel;
  std::array<double, PinholeRadtanCamera::kNumIntrinsics> intrinsics;

  template <class T>
  bool operator()(const T* s0, const T* s1, const T* s2, const T* s3, const T* landmark_p_W,
                  T* residual) const {
    const T* const control_points[4] = {s0, s1, s2, s3};
    const SE3<T> T_W_C = evaluateSe3Spline(control_points, T(u));
    std::array<T, PinholeRadtanCamera::kNumIntrinsics> k;
    for (int i = 0; i < PinholeRadtanCamera::kNumIntrinsics; ++i) k[i] = T(intrinsics[i]);
    const Vector2<T> predicted = projectPinhole(
        T_W_C, Vector3<T>(landmark_p_W[0], landmark_p_W[1], landmark_p_W[2]), k.data());
    residual[0] = predicted.x() - pixel.x();
    residual[1] = predicted.y() - pixel.y();
    return true;
  }
};

class SplineReprojectionFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 2;

  // Throws std::out_of_range when t_frame is outside the spline's valid range,
  // std::invalid_argument for a malformed timing, a noise model that is not
  // 2-dimensional, a non-finite pixel or invalid intrinsics.
  SplineReprojectionFactor(const SplineTiming& spline, double t_frame, Key landmark_p_W,
                           const Eigen::Vector2d& pixel, const PinholeRadtanParameters& intrinsics,
                           NoiseModel noise, RobustLoss robust_loss = RobustLoss::none());
  // The same with a camera shared among factors: a joint problem holds
  // millions of these, and a camera of its own in each factor and each cost
  // function was about 300 bytes of the ~1 kB a reprojection took.
  SplineReprojectionFactor(const SplineTiming& spline, double t_frame, Key landmark_p_W,
                           const Eigen::Vector2d& pixel,
                           std::shared_ptr<const PinholeRadtanCamera> camera, NoiseModel noise,
                           RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "SplineReprojectionFactor"; }
  // Analytic Jacobians (see the header comment).
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;
  // The same residual through ceres::AutoDiffCostFunction (reference for tests
  // and benchmarks; true ambient derivatives).
  std::unique_ptr<ceres::CostFunction> createAutoDiffCostFunction() const;

  double frameTime() const { return t_frame_; }
  // Index i of S(i), the first active control point, and u in [0, 1].
  const SplineSegment& segment() const { return segment_; }
  const Eigen::Vector2d& pixel() const { return pixel_; }

 private:
  double t_frame_;
  SplineSegment segment_;
  Eigen::Vector2d pixel_;
  std::shared_ptr<const PinholeRadtanCamera> camera_;
};

}  // namespace hsmap
