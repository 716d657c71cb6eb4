#include "pipelines/simulate/motion/vehicle_motion_config.h"

#include <cmath>
#include <stdexcept>

#include "core/survey/number_text.h"

namespace hsmap {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("VehicleMotionConfig: " + what);
}

void requirePositive(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    fail(std::string(name) + " must be a finite number > 0, got " + formatDouble(value));
  }
}

void requireInRange(double value, double low, double high, const char* name) {
  if (!(value >= low && value <= high)) {
    fail(std::string(name) + " must be in [" + formatDouble(low) + ", " + formatDouble(high) +
         "], got " + formatDouble(value));
  }
}

void requireFinite(double value, const char* name) {
  if (!std::isfinite(value)) fail(std::string(name) + " must be finite, got " + formatDouble(value));
}

}  // namespace

void VehicleMotionConfig::validate() const {
  requirePositive(length_m, "length_m");
  requirePositive(speed_m_s, "speed_m_s");
  // Below 1 - 0.9 the vehicle would nearly stop; the arc length must stay
  // strictly increasing in time.
  requireInRange(speed_variation, 0.0, 0.9, "speed_variation");
  requirePositive(altitude_m, "altitude_m");
  requireInRange(roll_pitch_amplitude_deg, 0.0, 45.0, "roll_pitch_amplitude_deg");
  requireInRange(heading_wander_deg, 0.0, 45.0, "heading_wander_deg");
  requireInRange(heading_deg, -360.0, 360.0, "heading_deg");
  if (pattern == MotionPattern::transect && lanes != 1) {
    fail("a transect has lanes = 1, got " + std::to_string(lanes) +
         " (use the lawnmower pattern for several lanes)");
  }
  if (pattern == MotionPattern::lawnmower) {
    if (lanes < 2) fail("a lawnmower needs lanes >= 2, got " + std::to_string(lanes));
    requirePositive(lane_spacing_m, "lane_spacing_m");
  }
  requireFinite(start_north_m, "start_north_m");
  requireFinite(start_east_m, "start_east_m");
  requireFinite(start_time_s, "start_time_s");
}

std::string motionPatternName(MotionPattern pattern) {
  return pattern == MotionPattern::lawnmower ? "lawnmower" : "transect";
}

MotionPattern parseMotionPattern(const std::string& name) {
  if (name == "transect") return MotionPattern::transect;
  if (name == "lawnmower") return MotionPattern::lawnmower;
  throw std::invalid_argument("unknown motion pattern '" + name +
                              "'; expected 'transect' or 'lawnmower'");
}

}  // namespace hsmap
