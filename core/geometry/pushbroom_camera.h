#pragma once
// PushbroomCamera: the UHI line camera of docs/SURVEY_FORMAT.md, in its frame U (z the
// optical axis, x along the sensor line, y across it).
//
//   x = x_U / z_U,   x_d = x (1 + k1 x^2 + k2 x^4),   u = f x_d + cx
//
// A scan line only sees points with y_U / z_U = 0 (within the instantaneous
// field of view), so the projection returns two numbers:
//   (u, y_U / z_U) = (pixel along the line, tangent of the across-line angle).
// A push-broom factor drives the second to zero and compares the first with
// the observed pixel. Pixel centres are at integer u; the line covers
// [-0.5, samples - 0.5).
//
// Intrinsics block for Ceres (4 scalars): [f cx k1 k2]. projectWith() does not
// test the depth: points with z_U <= 0 must be rejected by the caller.
//
// The distortion g(x) = x (1 + k1 x^2 + k2 x^4) is odd and increasing near 0;
// g'(x) = 1 + 3 k1 x^2 + 5 k2 x^4. Its monotonic region |x| < maxMonotonicTangent()
// (the first positive root of g', infinite when there is none) is where a pixel
// has exactly one ray: unproject() inverts g there by safeguarded Newton
// (bracketed, falling back to bisection) and returns std::nullopt for pixels
// beyond the fold.

#include <Eigen/Core>
#include <array>
#include <optional>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/matrix_types.h"

namespace hsmap {

class PushbroomCamera {
 public:
  static constexpr int kNumIntrinsics = 4;  // f cx k1 k2

  // Throws std::invalid_argument for non-positive samples or focal length, or
  // a non-finite value.
  explicit PushbroomCamera(const PushbroomParameters& parameters);

  const PushbroomParameters& parameters() const { return parameters_; }
  // [f cx k1 k2], the layout projectWith() expects.
  const std::array<double, kNumIntrinsics>& intrinsics() const { return intrinsics_; }
  int samples() const { return parameters_.samples; }

  template <class T>
  static Vector2<T> projectWith(const T* intrinsics, const Vector3<T>& p_U) {
    const T& f = intrinsics[0];
    const T& cx = intrinsics[1];
    const T& k1 = intrinsics[2];
    const T& k2 = intrinsics[3];
    const T x = p_U.x() / p_U.z();
    const T x2 = x * x;
    const T x_d = x * (T(1) + x2 * (k1 + k2 * x2));
    return Vector2<T>(f * x_d + cx, p_U.y() / p_U.z());
  }

  // projectWith() with this camera's intrinsics (cast to T).
  template <class T>
  Vector2<T> project(const Vector3<T>& p_U) const {
    std::array<T, kNumIntrinsics> intrinsics;
    for (int i = 0; i < kNumIntrinsics; ++i) intrinsics[i] = T(intrinsics_[i]);
    return projectWith(intrinsics.data(), p_U);
  }
  Eigen::Vector2d project(const Eigen::Vector3d& p_U) const {
    return projectWith(intrinsics_.data(), p_U);
  }

  // Unit ray in U with y = 0 and z > 0 through line pixel u; std::nullopt when
  // u lies beyond the monotonic region of the distortion.
  std::optional<Eigen::Vector3d> unproject(double u) const;

  bool isInLine(double u) const;

  // Bound on |x_U / z_U| of the monotonic region (+infinity when unbounded).
  double maxMonotonicTangent() const { return max_monotonic_tangent_; }

  // d project / d p_U (2x3) and d project / d intrinsics (2x4, intrinsics order).
  Eigen::Matrix<double, 2, 3> projectJacobianPoint(const Eigen::Vector3d& p_U) const;
  Eigen::Matrix<double, 2, kNumIntrinsics> projectJacobianIntrinsics(
      const Eigen::Vector3d& p_U) const;

 private:
  double distort(double x) const;            // g(x)
  double distortDerivative(double x) const;  // g'(x)

  PushbroomParameters parameters_;
  std::array<double, kNumIntrinsics> intrinsics_;
  double max_monotonic_tangent_;
};

}  // namespace hsmap
