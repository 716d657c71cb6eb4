#pragma once
// MapPlacement: how well the INS places and scales the geo-referenced map,
// and the file RUN/georef/map_placement.yaml that keeps it for the stages
// after georef (the joint stage adds the scale's share to the lever arm's
// 1-sigma) and for people:
//
//   format: hsmap-map-placement/1
//   fixes: 12                        INS fixes the similarity was fitted to
//   attitude: measured               measured | assumed (level, along-track)
//   scale_sigma: 0.0041              1-sigma of the map's relative scale
//   scale_sigma_without_attitude: 0.012   the same if the INS attitude were not used
//   scale_sigma_without_depth: 0.031      the same if the depths were as noisy as
//                                         the horizontal positions: what each part
//                                         of the INS contributes to the scale
//   rotation_sigma_deg: [r, p, h]    about W's north, east, down axes
//   position_sigma_m: [n, e, d]      of the map's centroid in W
//   correction_scale: 1.00012        the similarity applied after the bundle
//   correction_rotation_deg: 0.001     adjustment to reach the maximum-likelihood
//   correction_translation_m: 0.002    one (near identity)
//
// The sigmas are those of the maximum-likelihood similarity between the
// adjusted map and the INS fixes it kept (ins_similarity.h), the map's shape
// taken as exact: what the INS's stated noise allows, and no better.
// Reading is strict (strict_yaml_map.h): InputError naming the file, line
// and key.

#include <Eigen/Core>
#include <filesystem>
#include <string>

#include "core/survey/run_calibration.h"

namespace hsmap {

struct MapPlacement {
  static constexpr const char* kFormat = "hsmap-map-placement/1";
  int fixes = 0;
  bool attitude_measured = true;
  double scale_sigma = 0.0;
  double scale_sigma_without_attitude = 0.0;
  double scale_sigma_without_depth = 0.0;
  Eigen::Vector3d rotation_sigma_deg = Eigen::Vector3d::Zero();
  Eigen::Vector3d position_sigma_m = Eigen::Vector3d::Zero();
  double correction_scale = 1.0;
  double correction_rotation_deg = 0.0;
  double correction_translation_m = 0.0;
};

// Above this 1-sigma of the scale georef warns: every length measured on the
// map carries that uncertainty.
inline constexpr double kScaleSigmaWarning = 0.01;

// The warning's text for `placement` (empty when the scale is known within
// kScaleSigmaWarning).
std::string scaleWarning(const MapPlacement& placement);

// A calibration estimated in a map of this placement: the lever arm T_C_U
// is measured in the map's units, so a map whose scale is off by a fraction
// e gives a translation off by e t. Adds that to its 1-sigma (when it has
// one), Sigma_t += sigma_scale^2 t t^T, per axis
//     sigma_i = sqrt(sigma_i^2 + (sigma_scale t_i)^2),
// says so among its warnings, and adds scaleWarning() when there is one.
void addMapScaleUncertainty(RunCalibration& calibration, const MapPlacement& placement);

void writeMapPlacement(const std::filesystem::path& file, const MapPlacement& placement);
MapPlacement readMapPlacement(const std::filesystem::path& file);

}  // namespace hsmap
