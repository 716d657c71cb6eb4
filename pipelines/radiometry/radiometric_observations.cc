#include "pipelines/radiometry/radiometric_observations.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "pipelines/radiometry/lamp_geometry.h"

namespace hsmap {

void ObservationOptions::validate() const {
  auto fail = [](const std::string& field, const std::string& expected) {
    throw std::invalid_argument("radiometry observations: " + field + " must be " + expected);
  };
  if (!(cell_m > 0.0) || !std::isfinite(cell_m)) fail("cell_m", "a finite value > 0");
  if (max_lines <= 0) fail("max_lines", "> 0");
  if (sample_stride < 0) fail("sample_stride", ">= 0 (0: automatic)");
  if (min_per_cell < 2) fail("min_per_cell", ">= 2");
  if (max_per_cell < min_per_cell) fail("max_per_cell", ">= min_per_cell");
  if (max_points <= 0) fail("max_points", "> 0");
  cast.validate();
}

std::string RadiometricObservations::summary() const {
  std::ostringstream text;
  text << "radiometry: " << items.size() << " observations of " << points << " seabed points (" << bands
       << " bands) from " << lines_cast << " scan lines cast; " << pixels_hit << " pixels hit, " << pixels_unlit
       << " unlit (every lamp behind the surface or shadowed), " << lamp_paths_shadowed
       << " lamp paths shadowed, " << pixels_not_finite << " with a non-finite DN; " << cells_seen
       << " cells seen; UHI range " << uhi_range_min_m << "-" << uhi_range_max_m << " m, off-axis up to "
       << off_axis_max_rad * 180.0 / M_PI << " deg\n";
  return text.str();
}

RadiometricObservations gatherObservations(const EnviReader& cube, const PushbroomCamera& camera,
                                           const std::vector<LinePose>& line_poses, const MeshRayCaster& mesh,
                                           const LightsConfig& lights, const SE3d& T_C_U,
                                           const ObservationOptions& options) {
  options.validate();
  RadiometricObservations result;
  result.bands = cube.bands();
  const int samples = cube.samples();
  if (camera.samples() != samples) {
    throw std::invalid_argument("radiometry observations: the UHI camera has " + std::to_string(camera.samples()) +
                                " samples, the cube " + std::to_string(samples));
  }
  const int sample_stride = options.sample_stride > 0 ? options.sample_stride : std::max(1, samples / 48);
  const std::size_t line_stride =
      std::max<std::size_t>(1, (line_poses.size() + std::size_t(options.max_lines) - 1) / std::size_t(options.max_lines));

  const ScanLineCaster caster(camera, mesh, options.cast);
  std::map<std::pair<long long, long long>, std::vector<RadiometricObservation>> cells;
  ScanLineHits hits;
  std::vector<float> line_dn(std::size_t(samples) * std::size_t(result.bands));
  for (std::size_t i = 0; i < line_poses.size(); i += line_stride) {
    const LinePose& pose = line_poses[i];
    if (pose.line < 0 || pose.line >= cube.lines()) {
      throw std::invalid_argument("radiometry observations: scan line " + std::to_string(pose.line) +
                                  " is outside the cube's " + std::to_string(cube.lines()) + " lines");
    }
    caster.castLine(pose.line, pose.T, hits);
    ++result.lines_cast;
    if (hits.hits == 0) continue;
    cube.readLine(int(pose.line), line_dn.data());
    const LampsInWorld lamps = lampsInWorld(lights, pose.T, T_C_U);
    for (int s = sample_stride / 2; s < samples; s += sample_stride) {
      if (!hits.hit(s)) continue;
      ++result.pixels_hit;
      RadiometricObservation observation;
      observation.line = pose.line;
      observation.sample = s;
      observation.uhi_range_m = double(hits.range_m[std::size_t(s)]);
      observation.dn.resize(std::size_t(result.bands));
      bool finite = true;
      for (int b = 0; b < result.bands; ++b) {
        const float dn = line_dn[std::size_t(b) * std::size_t(samples) + std::size_t(s)];
        finite = finite && std::isfinite(dn);
        observation.dn[std::size_t(b)] = dn;
      }
      if (!finite) {
        ++result.pixels_not_finite;
        continue;
      }
      const Eigen::Vector3d& p_W = hits.p_W[std::size_t(s)];
      LampPathsAtPoint paths =
          lampPathsAt(lamps, p_W, triangleNormal(mesh, hits.triangle[std::size_t(s)]), pose.T.t, &mesh);
      result.lamp_paths_shadowed += paths.shadowed;
      if (paths.lit.empty()) {
        ++result.pixels_unlit;
        continue;
      }
      observation.lamps = std::move(paths.lit);
      const auto cell = std::make_pair((long long)std::floor(p_W.x() / options.cell_m),
                                       (long long)std::floor(p_W.y() / options.cell_m));
      cells[cell].push_back(std::move(observation));
    }
  }
  result.cells_seen = std::int64_t(cells.size());

  std::vector<std::vector<RadiometricObservation>*> kept;
  for (auto& [cell, observations] : cells) {
    if (int(observations.size()) >= options.min_per_cell) kept.push_back(&observations);
  }
  // At most max_points cells, evenly spread in the cells' order (north, then east).
  std::vector<std::vector<RadiometricObservation>*> chosen;
  if (int(kept.size()) <= options.max_points) {
    chosen = kept;
  } else {
    for (int k = 0; k < options.max_points; ++k) {
      chosen.push_back(kept[std::size_t((std::int64_t(k) * std::int64_t(kept.size())) / options.max_points)]);
    }
  }
  bool first = true;
  for (std::vector<RadiometricObservation>* observations : chosen) {
    const int point = result.points++;
    const std::size_t n = observations->size();
    const std::size_t keep = std::min<std::size_t>(n, std::size_t(options.max_per_cell));
    for (std::size_t k = 0; k < keep; ++k) {
      RadiometricObservation& observation = (*observations)[(k * n) / keep];
      observation.point = point;
      if (first) {
        result.uhi_range_min_m = result.uhi_range_max_m = observation.uhi_range_m;
        first = false;
      }
      result.uhi_range_min_m = std::min(result.uhi_range_min_m, observation.uhi_range_m);
      result.uhi_range_max_m = std::max(result.uhi_range_max_m, observation.uhi_range_m);
      for (const LampPath& lamp : observation.lamps) {
        result.off_axis_max_rad = std::max(result.off_axis_max_rad, lamp.off_axis_rad);
      }
      result.items.push_back(std::move(observation));
    }
  }
  return result;
}

}  // namespace hsmap
