#include "core/survey/lights_config.h"

#include <cmath>
#include <string>

#include "core/survey/calibration_yaml.h"
#include "core/survey/number_text.h"

namespace hsmap {
namespace {

// Lamps sit on the vehicle, as the sensors do (calibration_yaml.cc's bound
// on offsets between sensors).
constexpr double kMaxLampOffsetM = 100.0;
// As for quaternions (survey_config.h): hand-typed values are normalised,
// vectors that are far from unit are a mistake.
constexpr double kAxisNormTolerance = 1e-3;
// A few ulps of 1: the squared norm of a normalised vector lies within it.
constexpr double kUnitSquaredNormSlack = 1e-15;

Eigen::Vector3d lampPosition(const StrictYamlMap& lamp) {
  const std::vector<double> p = lamp.numbers("position_m", 3);
  for (std::size_t i = 0; i < 3; ++i) {
    if (std::abs(p[i]) > kMaxLampOffsetM) {
      lamp.fail("position_m", "expected coordinates in [-100, 100] m (the lamp's centre in C), got " +
                                  formatDouble(p[i]) + " at position " + std::to_string(i + 1));
    }
  }
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

Eigen::Vector3d lampAxis(const StrictYamlMap& lamp) {
  const std::vector<double> a = lamp.numbers("axis", 3);
  Eigen::Vector3d axis(a[0], a[1], a[2]);
  const double norm = axis.norm();
  if (norm == 0.0) {
    lamp.fail("axis", "expected a unit vector [x, y, z] (the beam's axis in C), got the zero vector");
  }
  if (std::abs(norm - 1.0) > kAxisNormTolerance) {
    lamp.fail("axis", "expected a unit vector [x, y, z] (norm within " +
                          formatDouble(kAxisNormTolerance) + " of 1), got norm " +
                          formatDouble(norm));
  }
  // Kept bit-identical when already unit (write -> read is an identity).
  if (std::abs(axis.squaredNorm() - 1.0) > kUnitSquaredNormSlack) axis.normalize();
  return axis;
}

void emitVector(YAML::Emitter& out, const char* key, const Eigen::Vector3d& v) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < 3; ++i) emitNumber(out, v[i]);
  out << YAML::EndSeq;
}

}  // namespace

LightsConfig readLightsConfig(const StrictYamlMap& lights) {
  LightsConfig config;
  config.response = lights.text("response");
  const std::vector<StrictYamlMap> lamps = lights.maps("lamps", {"position_m", "axis"});
  if (lamps.empty()) {
    lights.fail("lamps", "expected a non-empty list of lamps ({position_m, axis}), got an empty list");
  }
  for (const StrictYamlMap& lamp : lamps) {
    LampConfig value;
    value.p_C = lampPosition(lamp);
    value.axis_C = lampAxis(lamp);
    config.lamps.push_back(value);
  }
  return config;
}

void emitLightsConfig(YAML::Emitter& out, const LightsConfig& lights) {
  out << YAML::BeginMap;
  out << YAML::Key << "response" << YAML::Value << lights.response.generic_string();
  out << YAML::Key << "lamps" << YAML::Value << YAML::BeginSeq;
  for (const LampConfig& lamp : lights.lamps) {
    out << YAML::Flow << YAML::BeginMap;
    emitVector(out, "position_m", lamp.p_C);
    emitVector(out, "axis", lamp.axis_C);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::EndMap;
}

}  // namespace hsmap
