#pragma once
// LanePath: the planned horizontal path of a survey in W, parameterised by
// arc length s (metres): `lanes` straight lanes of length `lane_length_m`,
// lane k at east = start_east + k * lane_spacing_m, heading north for even k
// and south for odd k (a single lane is a transect), joined by U-turns.
//
// The turns are not circular arcs: a semicircle joined to a straight line has
// a curvature step, i.e. a jump in the vehicle's lateral acceleration and yaw
// rate. Instead the path heading turns by 180 degrees along a turn of arc
// length S with the quintic smoothstep g(u) = 10u^3 - 15u^4 + 6u^5, u = s'/S:
//   heading(s') = heading_lane + sign * pi * g(u),
// whose first and second derivatives vanish at both ends. The curvature
// (d heading / ds) therefore starts and ends at zero and its derivative is
// continuous too: position is C3 and heading C2 in s everywhere.
// The turn's displacement is S * (C(u), sign-adjusted S(u)) with
//   C(u) = integral_0^u cos(pi g), S(u) = integral_0^u sin(pi g),
// evaluated by Gauss-Legendre quadrature. g(1 - u) = 1 - g(u) makes
// C(1) = 0 (the turn ends level with where it began) and S = spacing / S(1)
// makes it end exactly on the next lane. Turns go east: clockwise (right)
// after northbound lanes, anticlockwise (left) after southbound ones, so the
// heading stays in [0, pi] and is continuous (never wrapped).
//
// A first-lane heading h (clockwise from north) turns the whole path about
// its start (start_north_m, start_east_m): every point's offset from the start
// is rotated by h and h is added to its heading, so the lanes run along h and
// h + pi and step towards h + pi/2 (to the right of the first lane). h = 0 is
// the north-heading path above, bit for bit.

#include <vector>

namespace hsmap {

struct PathPoint {
  double north_m = 0.0;
  double east_m = 0.0;
  double heading_rad = 0.0;  // direction of travel, from north towards east; continuous in s
};

class LanePath {
 public:
  // Throws std::invalid_argument unless lane_length_m > 0, lanes >= 1,
  // lane_spacing_m > 0 (when lanes >= 2) and every value is finite.
  LanePath(double lane_length_m, int lanes, double lane_spacing_m, double start_north_m,
           double start_east_m, double first_lane_heading_deg = 0.0);

  // Total arc length: lanes * lane length + (lanes - 1) * turn length.
  double length() const { return length_m_; }
  double laneLength() const { return lane_length_m_; }
  double turnLength() const { return turn_length_m_; }
  int lanes() const { return lanes_; }

  // The path point at arc length s, clamped to [0, length()].
  PathPoint at(double s) const;

 private:
  // The path point at s before the first-lane heading turns it.
  PathPoint northHeadingAt(double s) const;

  double lane_length_m_;
  int lanes_;
  double lane_spacing_m_;
  double start_north_m_;
  double start_east_m_;
  double first_lane_heading_rad_ = 0.0;
  double turn_length_m_ = 0.0;
  double length_m_ = 0.0;
};

}  // namespace hsmap
