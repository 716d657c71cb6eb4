#pragma once
// Soft floor on a point's depth before the perspective division of a camera
// factor (ReprojectionFactor, SplineReprojectionFactor, PushbroomLineFactor).
//
// The camera models (core/geometry) divide by the depth z and leave points
// with z <= 0 to the caller. A factor cannot simply return false there: Ceres
// would reject every step from a state in which one landmark of thousands has
// slipped behind a camera, and a NaN would poison the whole problem. Instead
// the depth goes through
//   z_eff(z) = z                              for z >= z_min
//   z_eff(z) = z_min^2 / (2 z_min - z)        for z <  z_min
// which is C1 at z_min (value z_min, slope 1), positive and increasing for
// every finite z, and tends to 0+ only as z -> -infinity. So the residual of
// a point behind (or at) the camera is large but finite, with a gradient
// that pulls the point in front of the camera again; the factor's robust
// loss bounds its weight. Front ends are still expected to drop such
// observations (and pipelines count them as outliers): this floor only keeps
// the solver's arithmetic sound while the estimate passes through them.
// No real observation is closer than z_min = 1 cm to a camera behind its
// housing port, so the floor never changes a valid residual.

namespace hsmap {

inline constexpr double kMinimumDepthM = 1e-2;

template <class T>
T softPositiveDepth(const T& z) {
  if (z >= T(kMinimumDepthM)) return z;
  return T(kMinimumDepthM * kMinimumDepthM) / (T(2.0 * kMinimumDepthM) - z);
}

}  // namespace hsmap
