#pragma once
// SplineTiming: the time grid of the trajectory spline that spline factors
// refer to (see core/geometry/se3_bspline.h): start time t0, knot spacing dt
// and number of control points N. Control point j of the spline is the
// factor-graph variable S(j) (a pose T_W_C, 7-scalar block), so a factor that
// knows the timing can name the control points active at a time.

#include <cstdint>
#include <vector>

#include "core/geometry/se3_bspline.h"
#include "core/graph/key.h"

namespace hsmap {

struct SplineTiming {
  double t0 = 0.0;             // s, time of the start of the valid range
  double dt = 0.0;             // s, knot spacing (> 0)
  int num_control_points = 0;  // N >= 4

  // Segment (first active control point i, u in [0, 1]) of time t; throws
  // std::out_of_range outside [t0, t0 + (N - 3) dt] and
  // std::invalid_argument for a malformed grid (splineSegmentAt()).
  SplineSegment segmentAt(double t) const { return splineSegmentAt(t, t0, dt, num_control_points); }

  template <class T>
  static SplineTiming of(const SE3Spline<T>& spline) {
    return {spline.t0(), spline.dt(), spline.numControlPoints()};
  }
};

// The keys S(i) .. S(i+3) of a segment's four active control points.
inline std::vector<Key> activeControlPointKeys(const SplineSegment& segment) {
  const auto i = static_cast<std::uint64_t>(segment.first_control_point);
  return {S(i), S(i + 1), S(i + 2), S(i + 3)};
}

}  // namespace hsmap
