#include "core/geometry/se3_bspline.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hsmap {

SplineSegment splineSegmentAt(double t, double t0, double dt, int num_control_points) {
  if (num_control_points < 4) {
    throw std::invalid_argument("splineSegmentAt: a cubic spline needs at least 4 control points, got " +
                                std::to_string(num_control_points));
  }
  if (!(std::isfinite(dt) && dt > 0.0)) {
    throw std::invalid_argument("splineSegmentAt: dt must be a positive finite number, got " +
                                std::to_string(dt));
  }
  const int num_segments = num_control_points - 3;
  // The end is computed as SE3Spline::validEnd() computes it, so that time is accepted.
  const double t_end = t0 + num_segments * dt;
  if (!(t >= t0 && t <= t_end)) {
    std::ostringstream message;
    message.precision(17);
    message << "splineSegmentAt: time " << t << " is outside the spline's valid range [" << t0
            << ", " << t_end << "]";
    throw std::out_of_range(message.str());
  }
  // Rounding may put s a hair outside [0, num_segments]: clamp before splitting.
  const double s = std::clamp((t - t0) / dt, 0.0, static_cast<double>(num_segments));
  const int first = std::min(static_cast<int>(std::floor(s)), num_segments - 1);
  return {first, s - first};
}

}  // namespace hsmap
