#pragma once
// SplineSmoothnessFactor: an optional regulariser on three consecutive control
// points of the trajectory spline, for stretches the measurements leave weakly
// determined (few landmarks, a gap in the video).
//
//   variables  S(i-1), S(i), S(i+1) (poses T_W_C, [qx qy qz qw tx ty tz])
//   residual   r = log(T_{i-1}^-1 T_i) - log(T_i^-1 T_{i+1})     (6, [rho; phi])
// Each log is the body-frame increment between neighbouring control points
// (se3.h's log, translation first: metres, radians), so r is the change of
// that increment from one knot interval to the next: zero for any motion at
// constant body twist (T_{i+1} = T_i exp(xi), T_i = T_{i-1} exp(xi)), which the
// cubic spline then reproduces exactly. For a uniform cubic B-spline the
// second difference of the control points is dt^2 times the second
// derivative at the knot, so r ~= -dt^2 [dv_B/dt ; domega_B/dt] for smooth
// motion: sigmas of sigma_linear_acceleration * dt^2 (m) and
// sigma_angular_acceleration * dt^2 (rad) express a prior on the vehicle's
// accelerations, independent of the knot spacing chosen.

#include <memory>
#include <string>

#include "core/geometry/se3.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"

namespace hsmap {

// Ceres functor: (T_{i-1} [7], T_i [7], T_{i+1} [7]) -> residual [6].
struct SplineSmoothnessResidual {
  template <class T>
  bool operator()(const T* previous, const T* current, const T* next, T* residual) const {
    const SE3<T> T_previous = SE3<T>::fromParameters(previous);
    const SE3<T> T_current = SE3<T>::fromParameters(current);
    const SE3<T> T_next = SE3<T>::fromParameters(next);
    const Vector6<T> r =
        (T_previous.inverse() * T_current).log() - (T_current.inverse() * T_next).log();
    for (int i = 0; i < 6; ++i) residual[i] = r[i];
    return true;
  }
};

class SplineSmoothnessFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 6;

  // Noise model [s_lin dt^2 (x3), s_ang dt^2 (x3)] from the accelerations'
  // sigmas (m/s^2, rad/s^2) and the knot spacing (s); see the header comment.
  // Throws std::invalid_argument for a value that is not positive and finite.
  static NoiseModel noiseFromAccelerationSigmas(double sigma_linear_acceleration,
                                                double sigma_angular_acceleration, double dt);

  // Keys S(i-1), S(i), S(i+1) for i >= 1. Throws std::invalid_argument for
  // i == 0 or a noise model that is not 6-dimensional.
  SplineSmoothnessFactor(std::uint64_t i, NoiseModel noise);
  // Any three consecutive pose variables, in order.
  SplineSmoothnessFactor(Key previous, Key current, Key next, NoiseModel noise);

  std::string name() const override { return "SplineSmoothnessFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;
};

}  // namespace hsmap
