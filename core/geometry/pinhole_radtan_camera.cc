#include "core/geometry/pinhole_radtan_camera.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace hsmap {

namespace {

void requireFinite(const char* name, double value) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(std::string("PinholeRadtanCamera: ") + name +
                                " must be finite, got " + std::to_string(value));
  }
}

void requirePositive(const char* name, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    throw std::invalid_argument(std::string("PinholeRadtanCamera: ") + name +
                                " must be a positive finite number, got " + std::to_string(value));
  }
}

constexpr int kMaxUndistortIterations = 50;
constexpr double kUndistortTolerance = 1e-12;
// Points along the axis-to-solution segment at which the distortion Jacobian
// determinant must be positive for the solution to lie in the one-to-one region.
constexpr int kMonotonicitySamples = 16;

}  // namespace

PinholeRadtanCamera::PinholeRadtanCamera(const PinholeRadtanParameters& parameters)
    : parameters_(parameters) {
  if (parameters.width <= 0 || parameters.height <= 0) {
    throw std::invalid_argument("PinholeRadtanCamera: width and height must be positive, got " +
                                std::to_string(parameters.width) + " x " +
                                std::to_string(parameters.height));
  }
  requirePositive("fx", parameters.fx);
  requirePositive("fy", parameters.fy);
  requireFinite("cx", parameters.cx);
  requireFinite("cy", parameters.cy);
  for (double k : parameters.distortion) requireFinite("distortion coefficient", k);
  const auto& d = parameters.distortion;
  intrinsics_ = {parameters.fx, parameters.fy, parameters.cx, parameters.cy,
                 d[0],          d[1],          d[2],          d[3],
                 d[4]};
}

Eigen::Vector2d PinholeRadtanCamera::distort(const Eigen::Vector2d& xy,
                                             Eigen::Matrix2d* jacobian) const {
  const double k1 = intrinsics_[4], k2 = intrinsics_[5], p1 = intrinsics_[6],
               p2 = intrinsics_[7], k3 = intrinsics_[8];
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const double d_radial_d_r2 = k1 + r2 * (2.0 * k2 + 3.0 * k3 * r2);
  if (jacobian != nullptr) {
    // d r2 / dx = 2x, d r2 / dy = 2y.
    (*jacobian)(0, 0) = radial + 2.0 * x * x * d_radial_d_r2 + 2.0 * p1 * y + 6.0 * p2 * x;
    (*jacobian)(0, 1) = 2.0 * x * y * d_radial_d_r2 + 2.0 * p1 * x + 2.0 * p2 * y;
    (*jacobian)(1, 0) = 2.0 * x * y * d_radial_d_r2 + 2.0 * p1 * x + 2.0 * p2 * y;
    (*jacobian)(1, 1) = radial + 2.0 * y * y * d_radial_d_r2 + 6.0 * p1 * y + 2.0 * p2 * x;
  }
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

std::optional<Eigen::Vector3d> PinholeRadtanCamera::unproject(const Eigen::Vector2d& pixel) const {
  if (!pixel.allFinite()) return std::nullopt;
  const Eigen::Vector2d target((pixel.x() - intrinsics_[2]) / intrinsics_[0],
                               (pixel.y() - intrinsics_[3]) / intrinsics_[1]);
  Eigen::Vector2d xy = target;  // the distortion is a perturbation of the identity
  bool converged = false;
  for (int iteration = 0; iteration < kMaxUndistortIterations; ++iteration) {
    Eigen::Matrix2d J;
    const Eigen::Vector2d residual = distort(xy, &J) - target;
    if (!(J.determinant() > 0.0)) return std::nullopt;  // at or beyond a fold
    // A residual at the rounding level of the target cannot be improved (near
    // a fold the step tolerance alone would never be met).
    if (residual.norm() <= 4.0 * std::numeric_limits<double>::epsilon() * target.norm()) {
      converged = true;
      break;
    }
    const Eigen::Vector2d step = J.partialPivLu().solve(residual);
    xy -= step;
    if (!xy.allFinite()) return std::nullopt;
    if (step.norm() <= kUndistortTolerance * (1.0 + xy.norm())) {
      converged = true;
      break;
    }
  }
  if (!converged) return std::nullopt;
  const double final_residual = (distort(xy, nullptr) - target).norm();
  if (final_residual > 1e-10 * (1.0 + target.norm())) return std::nullopt;
  // The solution must be reachable from the axis without crossing a fold;
  // otherwise another, inner solution may exist and this one is not the ray.
  for (int i = 1; i <= kMonotonicitySamples; ++i) {
    Eigen::Matrix2d J;
    distort(xy * (static_cast<double>(i) / kMonotonicitySamples), &J);
    if (!(J.determinant() > 0.0)) return std::nullopt;
  }
  return Eigen::Vector3d(xy.x(), xy.y(), 1.0).normalized();
}

bool PinholeRadtanCamera::isInImage(const Eigen::Vector2d& pixel) const {
  return pixel.x() >= -0.5 && pixel.x() < parameters_.width - 0.5 && pixel.y() >= -0.5 &&
         pixel.y() < parameters_.height - 0.5;
}

Eigen::Matrix<double, 2, 3> PinholeRadtanCamera::projectJacobianPoint(
    const Eigen::Vector3d& p_C) const {
  const double inv_z = 1.0 / p_C.z();
  const Eigen::Vector2d xy(p_C.x() * inv_z, p_C.y() * inv_z);
  Eigen::Matrix2d d_distorted_d_xy;
  distort(xy, &d_distorted_d_xy);
  Eigen::Matrix<double, 2, 3> d_xy_d_p;
  d_xy_d_p << inv_z, 0.0, -xy.x() * inv_z,
              0.0, inv_z, -xy.y() * inv_z;
  const Eigen::Matrix2d d_pixel_d_distorted =
      Eigen::Vector2d(intrinsics_[0], intrinsics_[1]).asDiagonal();
  return d_pixel_d_distorted * d_distorted_d_xy * d_xy_d_p;
}

Eigen::Matrix<double, 2, PinholeRadtanCamera::kNumIntrinsics>
PinholeRadtanCamera::projectJacobianIntrinsics(const Eigen::Vector3d& p_C) const {
  const double fx = intrinsics_[0], fy = intrinsics_[1];
  const double x = p_C.x() / p_C.z();
  const double y = p_C.y() / p_C.z();
  const double r2 = x * x + y * y;
  const Eigen::Vector2d distorted = distort(Eigen::Vector2d(x, y), nullptr);
  Eigen::Matrix<double, 2, kNumIntrinsics> J = Eigen::Matrix<double, 2, kNumIntrinsics>::Zero();
  // fx fy cx cy
  J(0, 0) = distorted.x();
  J(1, 1) = distorted.y();
  J(0, 2) = 1.0;
  J(1, 3) = 1.0;
  // k1 k2 (radial terms r2, r2^2 scale x and y)
  J(0, 4) = fx * x * r2;
  J(1, 4) = fy * y * r2;
  J(0, 5) = fx * x * r2 * r2;
  J(1, 5) = fy * y * r2 * r2;
  // p1 p2
  J(0, 6) = fx * 2.0 * x * y;
  J(1, 6) = fy * (r2 + 2.0 * y * y);
  J(0, 7) = fx * (r2 + 2.0 * x * x);
  J(1, 7) = fy * 2.0 * x * y;
  // k3
  J(0, 8) = fx * x * r2 * r2 * r2;
  J(1, 8) = fy * y * r2 * r2 * r2;
  return J;
}

}  // namespace hsmap
