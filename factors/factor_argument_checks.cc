#include "factors/factor_argument_checks.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace hsmap {

namespace {
constexpr double kUnitNormTolerance = 1e-6;
}  // namespace

void requireNoiseDimension(const char* factor_name, const NoiseModel& noise, int expected) {
  if (noise.dimension() != expected) {
    throw std::invalid_argument(std::string(factor_name) + ": the noise model has dimension " +
                                std::to_string(noise.dimension()) + ", expected " +
                                std::to_string(expected) + " (one per residual component)");
  }
}

Eigen::Quaterniond requireUnitQuaternion(const char* factor_name, const char* what,
                                         const Eigen::Quaterniond& q) {
  const double norm = q.norm();
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > kUnitNormTolerance) {
    std::ostringstream message;
    message.precision(17);
    message << factor_name << ": " << what << " must be a unit quaternion, got norm " << norm;
    throw std::invalid_argument(message.str());
  }
  return q.normalized();
}

SE3d requireRigidTransform(const char* factor_name, const char* what, const SE3d& T) {
  const std::string rotation_what = std::string(what) + " rotation";
  const Eigen::Quaterniond q = requireUnitQuaternion(factor_name, rotation_what.c_str(), T.q);
  requireFinite(factor_name, (std::string(what) + " translation").c_str(), T.t);
  return SE3d(q, T.t);
}

void requireFinite(const char* factor_name, const char* what, double value) {
  if (!std::isfinite(value)) {
    std::ostringstream message;
    message << factor_name << ": " << what << " must be finite, got " << value;
    throw std::invalid_argument(message.str());
  }
}

}  // namespace hsmap
