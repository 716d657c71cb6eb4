#include "core/geometry/pushbroom_camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace hsmap {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kMaxNewtonIterations = 100;

// Smallest positive root s of 1 + 3 k1 s + 5 k2 s^2 (s = x^2), +inf if none:
// the end of the region around the axis where g'(x) > 0.
double firstPositiveRootOfDerivative(double k1, double k2) {
  if (k2 == 0.0) return k1 < 0.0 ? -1.0 / (3.0 * k1) : kInfinity;
  const double a = 5.0 * k2, b = 3.0 * k1;
  const double discriminant = b * b - 4.0 * a;
  if (discriminant < 0.0) return kInfinity;  // g' never vanishes
  // Numerically stable roots: q = -(b + sign(b) sqrt(disc)) / 2, s = q / a and 1 / q.
  const double sign_b = b >= 0.0 ? 1.0 : -1.0;
  const double q = -0.5 * (b + sign_b * std::sqrt(discriminant));
  double smallest = kInfinity;
  for (double s : {q / a, 1.0 / q}) {
    if (s > 0.0 && s < smallest) smallest = s;
  }
  return smallest;
}

void requireFinite(const char* name, double value) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(std::string("PushbroomCamera: ") + name + " must be finite, got " +
                                std::to_string(value));
  }
}

}  // namespace

PushbroomCamera::PushbroomCamera(const PushbroomParameters& parameters)
    : parameters_(parameters) {
  if (parameters.samples <= 0) {
    throw std::invalid_argument("PushbroomCamera: samples must be positive, got " +
                                std::to_string(parameters.samples));
  }
  if (!(std::isfinite(parameters.f) && parameters.f > 0.0)) {
    throw std::invalid_argument("PushbroomCamera: f must be a positive finite number, got " +
                                std::to_string(parameters.f));
  }
  requireFinite("cx", parameters.cx);
  requireFinite("k1", parameters.distortion[0]);
  requireFinite("k2", parameters.distortion[1]);
  intrinsics_ = {parameters.f, parameters.cx, parameters.distortion[0], parameters.distortion[1]};
  max_monotonic_tangent_ =
      std::sqrt(firstPositiveRootOfDerivative(parameters.distortion[0], parameters.distortion[1]));
}

double PushbroomCamera::distort(double x) const {
  const double x2 = x * x;
  return x * (1.0 + x2 * (intrinsics_[2] + intrinsics_[3] * x2));
}

double PushbroomCamera::distortDerivative(double x) const {
  const double x2 = x * x;
  return 1.0 + x2 * (3.0 * intrinsics_[2] + 5.0 * intrinsics_[3] * x2);
}

std::optional<Eigen::Vector3d> PushbroomCamera::unproject(double u) const {
  if (!std::isfinite(u)) return std::nullopt;
  const double x_d = (u - intrinsics_[1]) / intrinsics_[0];
  // g is odd: solve for |x_d| on [0, hi] where g increases, then restore the sign.
  const double target = std::abs(x_d);
  double hi;
  if (std::isfinite(max_monotonic_tangent_)) {
    // At the fold itself the inverse has an infinite slope: reject it too.
    if (!(target < distort(max_monotonic_tangent_))) return std::nullopt;
    hi = max_monotonic_tangent_;
  } else {
    // g increases without bound: grow a bracket.
    hi = std::max(target, 1.0);
    for (int i = 0; i < 1100 && distort(hi) < target; ++i) hi *= 2.0;
    if (!(distort(hi) >= target)) return std::nullopt;
  }
  double lo = 0.0;
  double x = std::min(target, hi);
  bool converged = false;
  for (int iteration = 0; iteration < kMaxNewtonIterations; ++iteration) {
    const double residual = distort(x) - target;
    // Near the fold g' is small and rounding in the residual moves Newton's x
    // by more than the step tolerance: a residual at the rounding level of the
    // target is as converged as x can be.
    if (std::abs(residual) <= 4.0 * std::numeric_limits<double>::epsilon() * target) {
      converged = true;
      break;
    }
    if (residual > 0.0) {
      hi = x;
    } else {
      lo = x;
    }
    double next = x - residual / distortDerivative(x);
    if (!(next >= lo && next <= hi)) next = 0.5 * (lo + hi);  // Newton left the bracket
    const double change = std::abs(next - x);
    x = next;
    if (change <= 1e-15 * (1.0 + x)) {
      converged = true;
      break;
    }
  }
  if (!converged) return std::nullopt;
  const double tangent = x_d < 0.0 ? -x : x;
  return Eigen::Vector3d(tangent, 0.0, 1.0).normalized();
}

bool PushbroomCamera::isInLine(double u) const {
  return u >= -0.5 && u < parameters_.samples - 0.5;
}

Eigen::Matrix<double, 2, 3> PushbroomCamera::projectJacobianPoint(
    const Eigen::Vector3d& p_U) const {
  const double inv_z = 1.0 / p_U.z();
  const double x = p_U.x() * inv_z;
  const double du_dx = intrinsics_[0] * distortDerivative(x);
  Eigen::Matrix<double, 2, 3> J;
  J << du_dx * inv_z, 0.0, -du_dx * x * inv_z,
       0.0, inv_z, -p_U.y() * inv_z * inv_z;
  return J;
}

Eigen::Matrix<double, 2, PushbroomCamera::kNumIntrinsics>
PushbroomCamera::projectJacobianIntrinsics(const Eigen::Vector3d& p_U) const {
  const double x = p_U.x() / p_U.z();
  const double x3 = x * x * x;
  Eigen::Matrix<double, 2, kNumIntrinsics> J = Eigen::Matrix<double, 2, kNumIntrinsics>::Zero();
  J(0, 0) = distort(x);
  J(0, 1) = 1.0;
  J(0, 2) = intrinsics_[0] * x3;
  J(0, 3) = intrinsics_[0] * x3 * x * x;
  return J;
}

}  // namespace hsmap
