#pragma once
// PinholeRadtanCamera: OpenCV's pinhole model with radial-tangential
// distortion (the RGB camera C of docs/SURVEY_FORMAT.md; x right, y down, z forward).
//
//   x = X/Z, y = Y/Z, r2 = x^2 + y^2
//   radial = 1 + k1 r2 + k2 r2^2 + k3 r2^3
//   x_d = x radial + 2 p1 x y + p2 (r2 + 2 x^2)
//   y_d = y radial + p1 (r2 + 2 y^2) + 2 p2 x y
//   u = fx x_d + cx,  v = fy y_d + cy
// This is exactly cv::projectPoints with distCoeffs = [k1, k2, p1, p2, k3].
// Pixel centres are at integer coordinates; the image covers
// [-0.5, width - 0.5) x [-0.5, height - 0.5).
//
// Intrinsics block for Ceres (9 scalars): [fx fy cx cy k1 k2 p1 p2 k3].
// projectWith() does not test the depth: a point with Z <= 0 projects to a
// meaningless pixel, so callers (factors) must reject points behind the camera.
//
// unproject() inverts the distortion by Gauss-Newton (2x2 Newton steps on
// the normalised coordinates, started at the distorted coordinates). Valid
// region: the part of the normalised plane around the optical axis in which
// the distortion map is one-to-one, i.e. its Jacobian determinant stays
// positive along the segment from the axis to the solution. The result is
// std::nullopt when the iteration does not converge to 1e-12 in 50 steps or
// ends outside that region (e.g. a pixel beyond the fold of strong barrel
// distortion): such a pixel has no sound ray.

#include <Eigen/Core>
#include <array>
#include <optional>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/matrix_types.h"

namespace hsmap {

class PinholeRadtanCamera {
 public:
  static constexpr int kNumIntrinsics = 9;  // fx fy cx cy k1 k2 p1 p2 k3

  // Throws std::invalid_argument for a non-positive size or focal length, or
  // a non-finite value.
  explicit PinholeRadtanCamera(const PinholeRadtanParameters& parameters);

  const PinholeRadtanParameters& parameters() const { return parameters_; }
  // [fx fy cx cy k1 k2 p1 p2 k3], the layout projectWith() expects.
  const std::array<double, kNumIntrinsics>& intrinsics() const { return intrinsics_; }
  int width() const { return parameters_.width; }
  int height() const { return parameters_.height; }

  template <class T>
  static Vector2<T> projectWith(const T* intrinsics, const Vector3<T>& p_C) {
    const T& fx = intrinsics[0];
    const T& fy = intrinsics[1];
    const T& cx = intrinsics[2];
    const T& cy = intrinsics[3];
    const T& k1 = intrinsics[4];
    const T& k2 = intrinsics[5];
    const T& p1 = intrinsics[6];
    const T& p2 = intrinsics[7];
    const T& k3 = intrinsics[8];
    const T x = p_C.x() / p_C.z();
    const T y = p_C.y() / p_C.z();
    const T r2 = x * x + y * y;
    const T radial = T(1) + r2 * (k1 + r2 * (k2 + r2 * k3));
    const T x_d = x * radial + T(2) * p1 * x * y + p2 * (r2 + T(2) * x * x);
    const T y_d = y * radial + p1 * (r2 + T(2) * y * y) + T(2) * p2 * x * y;
    return Vector2<T>(fx * x_d + cx, fy * y_d + cy);
  }

  // projectWith() with this camera's intrinsics (cast to T).
  template <class T>
  Vector2<T> project(const Vector3<T>& p_C) const {
    std::array<T, kNumIntrinsics> intrinsics;
    for (int i = 0; i < kNumIntrinsics; ++i) intrinsics[i] = T(intrinsics_[i]);
    return projectWith(intrinsics.data(), p_C);
  }
  Eigen::Vector2d project(const Eigen::Vector3d& p_C) const {
    return projectWith(intrinsics_.data(), p_C);
  }

  // Unit ray in C (z > 0) through the pixel; std::nullopt outside the valid
  // region described in the header comment.
  std::optional<Eigen::Vector3d> unproject(const Eigen::Vector2d& pixel) const;

  bool isInImage(const Eigen::Vector2d& pixel) const;

  // d project / d p_C (2x3) and d project / d intrinsics (2x9, intrinsics order).
  Eigen::Matrix<double, 2, 3> projectJacobianPoint(const Eigen::Vector3d& p_C) const;
  Eigen::Matrix<double, 2, kNumIntrinsics> projectJacobianIntrinsics(
      const Eigen::Vector3d& p_C) const;

 private:
  // Distorted normalised coordinates of undistorted ones, and their 2x2 Jacobian.
  Eigen::Vector2d distort(const Eigen::Vector2d& xy, Eigen::Matrix2d* jacobian) const;

  PinholeRadtanParameters parameters_;
  std::array<double, kNumIntrinsics> intrinsics_;
};

}  // namespace hsmap
