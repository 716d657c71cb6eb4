#include "pipelines/surface/dense_surface.h"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "core/util/stage_timer.h"
#include "pipelines/surface/surface_reconstruction.h"
#include "pipelines/surface/surface_tiles.h"
#include "pipelines/surface/vertex_colours.h"
#include "pipelines/surface/voxel_point_fusion.h"

namespace hsmap {
namespace {

using Clock = std::chrono::steady_clock;

// At most `count` of `views`, evenly spaced through the list (the keyframes
// arrive in track order, so these are spread along the track).
std::vector<int> spreadViews(const std::vector<int>& views, int count) {
  if (int(views.size()) <= count) return views;
  if (count == 1) return {views.front()};
  std::vector<int> kept;
  for (std::size_t i = 0; i < std::size_t(count); ++i) {
    kept.push_back(views[i * (views.size() - 1) / std::size_t(count - 1)]);
  }
  return kept;
}

// Keeps as references only keyframes at least spacing_ratio x their depth
// from the previous reference along the survey: neighbouring keyframes see
// nearly the same seabed, and every point is still seen by many references.
void thinReferences(const VisualMap& map_W, double spacing_ratio,
                    std::vector<std::optional<StereoPartner>>& partners) {
  std::optional<Eigen::Vector3d> last;
  for (std::size_t k = 0; k < partners.size(); ++k) {
    if (!partners[k]) continue;
    const Eigen::Vector3d& c = map_W.keyframes()[k].T_F_C.t;
    if (last && (c - *last).norm() < spacing_ratio * partners[k]->median_depth_m) {
      partners[k].reset();
      continue;
    }
    last = c;
  }
}

}  // namespace

DenseSurfaceOptions::DenseSurfaceOptions() {
  // Dense points carry a few millimetres of noise: Labatut's soft visibility
  // keeps rays from carving the surface out from under their neighbours.
  cut.noise_sigma = 0.005;
  // A 7 px window rather than SGBM's 5: on weakly textured sand it lowers the
  // fused points' error (flat: 4.1 -> 3.8 mm, low-relief 2.8 -> 2.7 mm,
  // rugged 3.2 -> 3.2 mm median, completeness unchanged).
  stereo.block_size = 7;
  // The hull's rim is what long edges mark in a mesh of the whole swath; here
  // the tiles are cropped to their squares, and the long triangles left are
  // mostly those bridging a boulder's occluded flank to the ground, which the
  // relative test (5 x the 2 cm median edge) removed: on rugged completeness
  // 0.957 with it, 0.971 without, accuracy unchanged. Only triangles with an
  // edge over 0.5 m (more than any flank of the presets) go.
  cleaning.max_edge_factor = 0.0;
  cleaning.max_edge_m = 0.5;
}

std::string DenseSurfaceOptions::validate() const {
  if (std::string problem = partners.validate(); !problem.empty()) return problem;
  if (std::string problem = cut.validate(); !problem.empty()) return problem;
  if (std::string problem = cleaning.validate(); !problem.empty()) return problem;
  if (!(voxel_size_m > 0.0)) return "voxel_size_m must be > 0";
  if (min_support < 1) return "min_support must be at least 1";
  if (max_views_per_point < 1) return "max_views_per_point must be at least 1";
  if (!(tile_size_m >= 20.0 * voxel_size_m)) return "tile_size_m must be at least 20 voxels";
  if (!(tile_margin_m >= 0.0)) return "tile_margin_m must be >= 0";
  if (!(reference_spacing_ratio >= 0.0)) return "reference_spacing_ratio must be >= 0";
  return {};
}

std::string DenseSurfaceReport::summary() const {
  char text[1024];
  std::snprintf(text, sizeof(text),
                "dense points: %d of %d keyframes with a stereo partner, %d of them references, %d depth maps "
                "(%d failed), %.1f M depth points fused into %.2f M points in %d tiles "
                "(at most %d depth maps held at once); %.1f M visibility rays; "
                "cleaning removed %lld triangles; %d vertices seen by no keyframe (grey)\n"
                "  times: depth maps %.1f s, fusion %.1f s, graph cut %.1f s, cleaning %.1f s, "
                "colours %.1f s",
                keyframes_with_partner, keyframes, references, depth_maps, depth_maps_failed,
                double(depth_points) * 1e-6, double(fused_points) * 1e-6, tiles,
                max_depth_maps_held, double(rays) * 1e-6, static_cast<long long>(cleaned_triangles),
                uncoloured_vertices, seconds_depth, seconds_fusion, seconds_cut, seconds_cleaning,
                seconds_colour);
  return text;
}

DenseSurface reconstructDenseSurface(const VisualMap& map_W, const RgbFrameSource& frames,
                                     const PinholeRadtanCamera& camera,
                                     const DenseSurfaceOptions& options,
                                     const DenseSurfaceProgress& progress) {
  if (const std::string problem = options.validate(); !problem.empty()) {
    throw std::invalid_argument(problem);
  }
  DenseSurface surface;
  DenseSurfaceReport& report = surface.report;
  const auto& keyframes = map_W.keyframes();
  report.keyframes = int(keyframes.size());
  std::vector<std::optional<StereoPartner>> partners =
      selectStereoPartners(map_W, options.partners);
  for (const auto& partner : partners) report.keyframes_with_partner += partner ? 1 : 0;
  thinReferences(map_W, options.reference_spacing_ratio, partners);
  for (const auto& partner : partners) report.references += partner ? 1 : 0;
  if (report.keyframes_with_partner == 0) {
    throw std::runtime_error(
        "no keyframe has a stereo partner (a neighbour seeing the same landmarks at a baseline of " +
        std::to_string(options.partners.min_baseline_ratio) + " to " +
        std::to_string(options.partners.max_baseline_ratio) + " times the depth)");
  }
  std::vector<SurfaceTile> tiles =
      layOutTiles(map_W, partners, camera, options.tile_size_m, options.tile_margin_m);
  report.tiles = int(tiles.size());

  // How many tiles still need each keyframe's depth map.
  std::vector<int> tiles_needing(keyframes.size(), 0);
  for (const SurfaceTile& tile : tiles) {
    for (int k : tile.keyframes) ++tiles_needing[std::size_t(k)];
  }
  std::vector<Eigen::Vector3d> c_W;
  for (const Keyframe& keyframe : keyframes) c_W.push_back(keyframe.T_F_C.t);

  std::unordered_map<int, std::vector<Eigen::Vector3f>> depth_maps;  // held, in W
  std::mutex frames_mutex;  // RgbFrameSource is not thread-safe
  // Voxel key -> (output vertex, tile that made it): a later tile reuses the
  // vertex of a seam point; copies of one point within a tile (the cleaning
  // splits non-manifold vertices) stay apart.
  std::unordered_map<std::uint64_t, std::pair<int, int>> vertex_of_key;
  int depth_maps_done = 0;

  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const SurfaceTile& tile = tiles[t];
    // Depth maps this tile needs that are not held yet, computed in parallel.
    std::vector<int> missing;
    for (int k : tile.keyframes) {
      if (!depth_maps.count(k)) missing.push_back(k);
    }
    auto start = Clock::now();
    std::vector<std::optional<std::vector<Eigen::Vector3f>>> computed(missing.size());
    tbb::parallel_for(std::size_t(0), missing.size(), [&](std::size_t i) {
      const StereoPartner& partner = *partners[std::size_t(missing[i])];
      const Keyframe& reference = map_W.keyframe(partner.keyframe);
      const Keyframe& other = map_W.keyframe(partner.partner);
      cv::Mat image_reference, image_other;
      {
        std::lock_guard<std::mutex> lock(frames_mutex);
        image_reference = frames.frame(reference.frame_index);
        image_other = frames.frame(other.frame_index);
      }
      StereoPairOptions stereo = options.stereo;
      stereo.min_depth_m = partner.min_depth_m;
      stereo.max_depth_m = partner.max_depth_m;
      const StereoPairPoints pair = stereoPairPoints(image_reference, image_other, camera,
                                                     reference.T_F_C, other.T_F_C, stereo);
      if (!pair.skipped.empty()) return;  // no points from this pair: counted below
      std::vector<Eigen::Vector3f> points;
      points.reserve(pair.p_W.size());
      for (const Eigen::Vector3d& p : pair.p_W) points.push_back(p.cast<float>());
      computed[i] = std::move(points);
    });
    for (std::size_t i = 0; i < missing.size(); ++i) {
      if (computed[i]) {
        ++report.depth_maps;
        report.depth_points += std::int64_t(computed[i]->size());
        depth_maps[missing[i]] = std::move(*computed[i]);
      } else {
        ++report.depth_maps_failed;
        depth_maps[missing[i]] = {};
      }
    }
    report.max_depth_maps_held = std::max(report.max_depth_maps_held, int(depth_maps.size()));
    report.seconds_depth += secondsSince(start);
    depth_maps_done += int(missing.size());
    if (progress) progress("depth maps", depth_maps_done, report.references);

    // Fuse the points of the padded square.
    start = Clock::now();
    VoxelPointFusion fusion(options.voxel_size_m);
    for (int k : tile.keyframes) {
      const int partner = partners[std::size_t(k)]->partner;
      for (const Eigen::Vector3f& p : depth_maps[k]) {
        if (tile.padded.contains(p.head<2>().cast<double>())) fusion.add(p.cast<double>(), k, partner);
      }
    }
    const FusedPoints fused = fusion.extract(options.min_support);
    report.fused_points += std::int64_t(fused.p_W.size());
    report.seconds_fusion += secondsSince(start);

    if (fused.p_W.size() >= 4) {
      VisibilityPoints points;
      points.p_W = fused.p_W;
      points.views.reserve(fused.views.size());
      for (const std::vector<int>& views : fused.views) {
        points.views.push_back(spreadViews(views, options.max_views_per_point));
      }
      points.c_W = c_W;
      start = Clock::now();
      std::optional<SurfaceReconstruction> reconstruction;
      try {
        reconstruction = reconstructSurface(points, options.cut);
      } catch (const std::runtime_error& failure) {
        report.warnings.push_back("tile " + std::to_string(t) + ": " + failure.what());
      }
      report.seconds_cut += secondsSince(start);
      if (reconstruction) {
        report.rays += reconstruction->report.rays;
        start = Clock::now();
        MeshCleaningReport cleaning;
        const SurfaceMesh cleaned = cleanMesh(reconstruction->mesh, options.cleaning, &cleaning);
        report.cleaned_triangles +=
            std::int64_t(reconstruction->mesh.triangles.size() - cleaned.triangles.size());
        const SurfaceMesh kept = cropToTile(cleaned, tile.core);
        report.seconds_cleaning += secondsSince(start);

        start = Clock::now();
        const VertexColours colours =
            colourVerticesFromKeyframes(kept, points, map_W, frames, camera);
        report.uncoloured_vertices += colours.uncoloured;
        report.seconds_colour += secondsSince(start);
        // Stitch: a point of the seam has the same voxel key in both tiles.
        std::vector<int> global(kept.vertices.size());
        for (std::size_t v = 0; v < kept.vertices.size(); ++v) {
          const std::uint64_t key = fused.keys[std::size_t(kept.point_index[v])];
          const auto found = vertex_of_key.find(key);
          if (found != vertex_of_key.end() && found->second.second != int(t)) {
            global[v] = found->second.first;
            continue;
          }
          global[v] = int(surface.vertices.size());
          surface.vertices.push_back(kept.vertices[v]);
          surface.colours.push_back(colours.rgb[v]);
          if (found == vertex_of_key.end()) vertex_of_key.emplace(key, std::pair{global[v], int(t)});
        }
        for (const Eigen::Vector3i& triangle : kept.triangles) {
          const Eigen::Vector3i stitched(global[std::size_t(triangle[0])],
                                         global[std::size_t(triangle[1])],
                                         global[std::size_t(triangle[2])]);
          if (stitched[0] == stitched[1] || stitched[1] == stitched[2] || stitched[0] == stitched[2]) {
            continue;
          }
          surface.triangles.push_back(stitched);
        }
      }
    }
    // Depth maps no later tile needs are freed.
    for (int k : tile.keyframes) {
      if (--tiles_needing[std::size_t(k)] == 0) depth_maps.erase(k);
    }
    if (progress) progress("tiles", int(t) + 1, int(tiles.size()));
  }
  return surface;
}

}  // namespace hsmap
