#include "pipelines/georef/map_placement.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <sstream>

#include "core/io/atomic_file.h"
#include "core/survey/number_text.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"

namespace hsmap {
namespace {

std::string listOf(const Eigen::Vector3d& v) {
  return "[" + formatDouble(v[0]) + ", " + formatDouble(v[1]) + ", " + formatDouble(v[2]) + "]";
}

Eigen::Vector3d nonNegativeTriple(const StrictYamlMap& map, const std::string& key) {
  const std::vector<double> values = map.numbers(key, 3);
  for (double v : values) {
    if (!(v >= 0.0)) map.fail(key, "expected 3 numbers >= 0, got " + formatDouble(v));
  }
  return Eigen::Vector3d(values[0], values[1], values[2]);
}

}  // namespace

std::string scaleWarning(const MapPlacement& placement) {
  if (!(placement.scale_sigma > kScaleSigmaWarning)) return "";
  std::ostringstream text;
  text << "the map's scale is known to " << fixedDecimals(100.0 * placement.scale_sigma, 2)
       << " % only (1-sigma, from " << placement.fixes << " INS fixes"
       << (placement.attitude_measured ? "" : " without attitude")
       << "): every length measured on the map carries that uncertainty; a longer track or a "
          "change of depth"
       << (placement.attitude_measured ? "" : ", or INS attitude,") << " would tighten it";
  return text.str();
}

void addMapScaleUncertainty(RunCalibration& calibration, const MapPlacement& placement) {
  if (calibration.sigma_translation_m) {
    const Eigen::Vector3d scale_part = placement.scale_sigma * calibration.T_C_U.translation_m.cwiseAbs();
    calibration.sigma_translation_m =
        (calibration.sigma_translation_m->cwiseAbs2() + scale_part.cwiseAbs2()).cwiseSqrt().eval();
    calibration.warnings.push_back(
        "T_C_U's translation 1-sigma includes the map's scale uncertainty (" +
        fixedDecimals(100.0 * placement.scale_sigma, 2) +
        " %, georef/map_placement.yaml): a lever arm measured in the map is as uncertain as its scale");
  }
  const std::string warning = scaleWarning(placement);
  if (!warning.empty() && std::find(calibration.warnings.begin(), calibration.warnings.end(), warning) ==
                              calibration.warnings.end()) {
    calibration.warnings.push_back(warning);
  }
}

void writeMapPlacement(const std::filesystem::path& file, const MapPlacement& p) {
  std::ostringstream text;
  text << "format: " << MapPlacement::kFormat << "\n"
       << "fixes: " << p.fixes << "\n"
       << "attitude: " << (p.attitude_measured ? "measured" : "assumed") << "\n"
       << "scale_sigma: " << formatDouble(p.scale_sigma) << "\n"
       << "scale_sigma_without_attitude: " << formatDouble(p.scale_sigma_without_attitude) << "\n"
       << "scale_sigma_without_depth: " << formatDouble(p.scale_sigma_without_depth) << "\n"
       << "rotation_sigma_deg: " << listOf(p.rotation_sigma_deg) << "\n"
       << "position_sigma_m: " << listOf(p.position_sigma_m) << "\n"
       << "correction_scale: " << formatDouble(p.correction_scale) << "\n"
       << "correction_rotation_deg: " << formatDouble(p.correction_rotation_deg) << "\n"
       << "correction_translation_m: " << formatDouble(p.correction_translation_m) << "\n";
  writeTextAtomically(file, text.str());
}

MapPlacement readMapPlacement(const std::filesystem::path& file) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& error) {
    throw InputError(file, "line " + std::to_string(error.mark.line + 1), error.msg);
  }
  const StrictYamlMap map(file, root, "", 1,
                          {"format", "fixes", "attitude", "scale_sigma", "scale_sigma_without_attitude",
                           "scale_sigma_without_depth", "rotation_sigma_deg",
                           "position_sigma_m", "correction_scale", "correction_rotation_deg",
                           "correction_translation_m"});
  if (map.text("format") != MapPlacement::kFormat) {
    map.fail("format", std::string("expected ") + MapPlacement::kFormat + ", got '" +
                           map.text("format") + "'");
  }
  MapPlacement p;
  p.fixes = map.positiveInteger("fixes");
  const std::string attitude = map.text("attitude");
  if (attitude != "measured" && attitude != "assumed") {
    map.fail("attitude", "expected measured or assumed, got '" + attitude + "'");
  }
  p.attitude_measured = attitude == "measured";
  p.scale_sigma = map.numberInRange("scale_sigma", 0.0, 1e6);
  p.scale_sigma_without_attitude = map.numberInRange("scale_sigma_without_attitude", 0.0, 1e6);
  p.scale_sigma_without_depth = map.numberInRange("scale_sigma_without_depth", 0.0, 1e6);
  p.rotation_sigma_deg = nonNegativeTriple(map, "rotation_sigma_deg");
  p.position_sigma_m = nonNegativeTriple(map, "position_sigma_m");
  p.correction_scale = map.positiveNumber("correction_scale");
  p.correction_rotation_deg = map.numberInRange("correction_rotation_deg", 0.0, 180.0);
  p.correction_translation_m = map.numberInRange("correction_translation_m", 0.0, 1e9);
  return p;
}

}  // namespace hsmap
