#pragma once
// Checks shared by the factor constructors. A factor built from a wrong noise
// model or a non-rotation would give a solver silently wrong weights, so each
// constructor validates its arguments and throws std::invalid_argument with a
// message naming the factor, what was expected and what was found.

#include <Eigen/Geometry>

#include "core/geometry/se3.h"
#include "core/graph/noise_model.h"

namespace hsmap {

// The noise model must have one row per residual component.
void requireNoiseDimension(const char* factor_name, const NoiseModel& noise, int expected);

// A measured or prior rotation must be a unit quaternion (|q| within 1e-6 of
// 1: a looser quaternion is a caller's bug, not rounding). Returns q
// normalised to full precision.
Eigen::Quaterniond requireUnitQuaternion(const char* factor_name, const char* what,
                                         const Eigen::Quaterniond& q);
// The same for the rotation of a pose, plus a finite translation.
SE3d requireRigidTransform(const char* factor_name, const char* what, const SE3d& T);

// A measurement (pixel, position, time) must be finite.
void requireFinite(const char* factor_name, const char* what, double value);
template <class Derived>
void requireFinite(const char* factor_name, const char* what, const Eigen::MatrixBase<Derived>& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) requireFinite(factor_name, what, double(v(i)));
}

}  // namespace hsmap
