#include "core/survey/camera_sigma.h"

#include <algorithm>
#include <vector>

#include "core/survey/calibration_yaml.h"
#include "core/survey/number_text.h"

namespace hsmap {
namespace {

// The bounds of the camera values themselves (calibration_yaml.cc): a sigma
// larger than any valid focal length or coefficient is damage, not doubt.
constexpr double kMaxPixelSigma = 1e6;
constexpr double kMaxDistortionSigma = 1000.0;

double pixelSigma(const StrictYamlMap& sigma, const std::string& key) {
  return sigma.numberInRange(key, 0.0, kMaxPixelSigma, 0.0);
}

template <std::size_t N>
std::array<double, N> distortionSigma(const StrictYamlMap& sigma) {
  const std::vector<double> values = sigma.numbers("distortion", N, std::vector<double>(N, 0.0));
  std::array<double, N> result{};
  for (std::size_t i = 0; i < N; ++i) {
    if (values[i] < 0.0 || values[i] > kMaxDistortionSigma) {
      sigma.fail("distortion", "expected " + std::to_string(N) + " sigmas in [0, 1000], got " +
                                   formatDouble(values[i]) + " at position " +
                                   std::to_string(i + 1));
    }
    result[i] = values[i];
  }
  return result;
}

template <std::size_t N>
bool anyPositive(const std::array<double, N>& values) {
  return std::any_of(values.begin(), values.end(), [](double v) { return v > 0.0; });
}

void emitKey(YAML::Emitter& out, const char* key, double value) {
  out << YAML::Key << key << YAML::Value;
  emitNumber(out, value);
}

template <std::size_t N>
void emitDistortion(YAML::Emitter& out, const std::array<double, N>& values) {
  out << YAML::Key << "distortion" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (double v : values) emitNumber(out, v);
  out << YAML::EndSeq;
}

}  // namespace

bool PinholeRadtanSigma::asksForCalibration() const {
  return fx > 0.0 || fy > 0.0 || cx > 0.0 || cy > 0.0 || anyPositive(distortion);
}

bool PushbroomSigma::asksForCalibration() const {
  return f > 0.0 || cx > 0.0 || anyPositive(distortion);
}

PinholeRadtanSigma readPinholeRadtanSigma(const StrictYamlMap& parent, const std::string& key) {
  const StrictYamlMap map = parent.map(key, {"fx", "fy", "cx", "cy", "distortion"});
  PinholeRadtanSigma sigma;
  sigma.fx = pixelSigma(map, "fx");
  sigma.fy = pixelSigma(map, "fy");
  sigma.cx = pixelSigma(map, "cx");
  sigma.cy = pixelSigma(map, "cy");
  sigma.distortion = distortionSigma<5>(map);
  return sigma;
}

PushbroomSigma readPushbroomSigma(const StrictYamlMap& parent, const std::string& key) {
  const StrictYamlMap map = parent.map(key, {"f", "cx", "distortion"});
  PushbroomSigma sigma;
  sigma.f = pixelSigma(map, "f");
  sigma.cx = pixelSigma(map, "cx");
  sigma.distortion = distortionSigma<2>(map);
  return sigma;
}

void emitPinholeRadtanSigma(YAML::Emitter& out, const PinholeRadtanSigma& sigma) {
  out << YAML::Flow << YAML::BeginMap;
  emitKey(out, "fx", sigma.fx);
  emitKey(out, "fy", sigma.fy);
  emitKey(out, "cx", sigma.cx);
  emitKey(out, "cy", sigma.cy);
  emitDistortion(out, sigma.distortion);
  out << YAML::EndMap;
}

void emitPushbroomSigma(YAML::Emitter& out, const PushbroomSigma& sigma) {
  out << YAML::Flow << YAML::BeginMap;
  emitKey(out, "f", sigma.f);
  emitKey(out, "cx", sigma.cx);
  emitDistortion(out, sigma.distortion);
  out << YAML::EndMap;
}

}  // namespace hsmap
