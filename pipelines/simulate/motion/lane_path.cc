#include "pipelines/simulate/motion/lane_path.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace hsmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Gauss-Legendre rule on [-1, 1]. 20 nodes integrate cos/sin(pi g(u)) on any
// [0, u], u <= 1, to ~1e-16 (16 nodes leave 2e-12 on [0, 1], measured against
// a 2-million-panel Simpson sum in long double).
constexpr int kQuadratureNodes = 20;

struct QuadratureRule {
  std::array<double, kQuadratureNodes> node{};
  std::array<double, kQuadratureNodes> weight{};
};

// Nodes are the roots of the Legendre polynomial P_n, found by Newton from
// the classic estimate cos(pi (i + 3/4) / (n + 1/2)); weights 2 / ((1 - x^2) P_n'(x)^2).
QuadratureRule makeGaussLegendreRule() {
  QuadratureRule rule;
  const int n = kQuadratureNodes;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double derivative = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p_previous = 1.0;  // P_0
      double p = x;             // P_1
      for (int k = 2; k <= n; ++k) {
        const double p_next = ((2.0 * k - 1.0) * x * p - (k - 1.0) * p_previous) / k;
        p_previous = p;
        p = p_next;
      }
      derivative = n * (x * p - p_previous) / (x * x - 1.0);
      const double step = p / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    rule.node[i] = x;
    rule.weight[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
  return rule;
}

const QuadratureRule& gaussLegendreRule() {
  static const QuadratureRule rule = makeGaussLegendreRule();
  return rule;
}

// Quintic smoothstep: g(0) = 0, g(1) = 1, g' and g'' zero at both ends.
double smoothstep5(double u) { return u * u * u * (10.0 + u * (-15.0 + 6.0 * u)); }

// (C(u), S(u)) = integral_0^u (cos, sin)(pi g(v)) dv.
std::array<double, 2> turnDisplacement(double u) {
  const QuadratureRule& rule = gaussLegendreRule();
  double c = 0.0;
  double s = 0.0;
  for (int i = 0; i < kQuadratureNodes; ++i) {
    const double v = 0.5 * u * (rule.node[i] + 1.0);
    const double angle = kPi * smoothstep5(v);
    c += rule.weight[i] * std::cos(angle);
    s += rule.weight[i] * std::sin(angle);
  }
  return {0.5 * u * c, 0.5 * u * s};
}

void requireFinite(double value, const char* name) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument(std::string("LanePath: ") + name + " must be finite");
  }
}

}  // namespace

LanePath::LanePath(double lane_length_m, int lanes, double lane_spacing_m, double start_north_m,
                   double start_east_m, double first_lane_heading_deg)
    : lane_length_m_(lane_length_m),
      lanes_(lanes),
      lane_spacing_m_(lane_spacing_m),
      start_north_m_(start_north_m),
      start_east_m_(start_east_m),
      first_lane_heading_rad_(first_lane_heading_deg * kPi / 180.0) {
  requireFinite(start_north_m, "start_north_m");
  requireFinite(start_east_m, "start_east_m");
  requireFinite(first_lane_heading_deg, "first_lane_heading_deg");
  if (!(lane_length_m > 0.0) || !std::isfinite(lane_length_m)) {
    throw std::invalid_argument("LanePath: lane length must be a finite number > 0 m");
  }
  if (lanes < 1) {
    throw std::invalid_argument("LanePath: expected at least 1 lane, got " +
                                std::to_string(lanes));
  }
  if (lanes >= 2) {
    if (!(lane_spacing_m > 0.0) || !std::isfinite(lane_spacing_m)) {
      throw std::invalid_argument("LanePath: lane spacing must be a finite number > 0 m");
    }
    turn_length_m_ = lane_spacing_m / turnDisplacement(1.0)[1];
  }
  length_m_ = lanes * lane_length_m + (lanes - 1) * turn_length_m_;
}

PathPoint LanePath::at(double s) const {
  PathPoint point = northHeadingAt(s);
  // Skipped at heading 0 so that the default path keeps its exact bits.
  if (first_lane_heading_rad_ == 0.0) return point;
  const double cos_h = std::cos(first_lane_heading_rad_);
  const double sin_h = std::sin(first_lane_heading_rad_);
  const double north = point.north_m - start_north_m_;
  const double east = point.east_m - start_east_m_;
  // Clockwise (north towards east) rotation by h in the (north, east) plane.
  point.north_m = start_north_m_ + cos_h * north - sin_h * east;
  point.east_m = start_east_m_ + sin_h * north + cos_h * east;
  point.heading_rad += first_lane_heading_rad_;
  return point;
}

PathPoint LanePath::northHeadingAt(double s) const {
  s = std::clamp(s, 0.0, length_m_);
  const double period = lane_length_m_ + turn_length_m_;
  const int lane = std::min(static_cast<int>(s / period), lanes_ - 1);
  const double along = s - lane * period;
  const bool northbound = lane % 2 == 0;
  const double lane_east = start_east_m_ + lane * lane_spacing_m_;
  PathPoint point;
  if (along <= lane_length_m_ || lane == lanes_ - 1) {
    const double on_lane = std::min(along, lane_length_m_);
    point.north_m = start_north_m_ + (northbound ? on_lane : lane_length_m_ - on_lane);
    point.east_m = lane_east;
    point.heading_rad = northbound ? 0.0 : kPi;
    return point;
  }
  // In the turn after `lane`: north end for northbound lanes, south end otherwise.
  const double u = (along - lane_length_m_) / turn_length_m_;
  const std::array<double, 2> displacement = turnDisplacement(u);
  const double turned = kPi * smoothstep5(u);
  if (northbound) {
    point.north_m = start_north_m_ + lane_length_m_ + turn_length_m_ * displacement[0];
    point.heading_rad = turned;
  } else {
    point.north_m = start_north_m_ - turn_length_m_ * displacement[0];
    point.heading_rad = kPi - turned;
  }
  point.east_m = lane_east + turn_length_m_ * displacement[1];
  return point;
}

}  // namespace hsmap
