#include "pipelines/evaluate/mesh_metrics.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

#include "core/raycast/mesh_ray_caster.h"
#include "core/util/input_error.h"
#include "core/util/median.h"
#include "pipelines/evaluate/triangle_mesh_distance.h"

namespace hsmap {
namespace {

// Why the metrics are missing when the run wrote no mesh.
constexpr const char* kNoMesh = "RUN/map/mesh.ply not found: the run has no surface stage";

// The median (the mean of the two middle values for an even count) of a
// non-empty list, taken by value because nth_element reorders it.
MeshMetrics bothMissing(const std::string& why) {
  return {MetricValue::missing(why), MetricValue::missing(why), 0};
}

}  // namespace

void MeshMetricsOptions::validate() const {
  if (!std::isfinite(completeness_distance_m) || completeness_distance_m <= 0.0) {
    throw std::invalid_argument("MeshMetricsOptions: completeness_distance_m must be finite and > 0");
  }
  if (max_footprint_samples <= 0) {
    throw std::invalid_argument("MeshMetricsOptions: max_footprint_samples must be > 0");
  }
}

std::vector<MeshMetrics> computeMeshMetrics(const PlyMesh& mesh_est,
                                            const std::vector<Sim3>& alignments,
                                            const PlyMesh& true_scene,
                                            const std::vector<Eigen::Vector3d>& true_samples_W,
                                            double completeness_distance_m) {
  if (mesh_est.vertices.empty()) {
    throw std::invalid_argument("computeMeshMetrics: the produced mesh has no vertices");
  }
  std::vector<MeshMetrics> metrics(alignments.size());
  const auto mapped = [&](const Sim3& S_true_est) {
    std::vector<Eigen::Vector3d> vertices_true;
    vertices_true.reserve(mesh_est.vertices.size());
    for (const Eigen::Vector3d& v : mesh_est.vertices) vertices_true.push_back(S_true_est.apply(v));
    return vertices_true;
  };
  {
    // One tree at a time: a 100 m transect's true scene has millions of
    // triangles, and its tree is freed before a produced mesh's is built.
    const TriangleMeshDistance true_surface(true_scene.vertices, true_scene.triangles);
    for (std::size_t a = 0; a < alignments.size(); ++a) {
      metrics[a].mesh_accuracy_m =
          MetricValue::of(median(true_surface.distances(mapped(alignments[a]))));
    }
  }

  for (std::size_t a = 0; a < alignments.size(); ++a) {
    MeshMetrics& out = metrics[a];
    if (mesh_est.triangles.empty()) {
      out.mesh_completeness = MetricValue::missing(
          "RUN/map/mesh.ply has no triangles: completeness needs a surface, not a point cloud");
      continue;
    }
    if (true_samples_W.empty()) {
      out.mesh_completeness = MetricValue::missing(
          "no true-surface sample: truth/reflectance has no valid pixel over truth/scene.ply");
      continue;
    }
    std::optional<TriangleMeshDistance> mesh_true;
    try {
      mesh_true.emplace(mapped(alignments[a]), mesh_est.triangles);
    } catch (const std::invalid_argument& e) {
      // Only degenerate triangles: a surface of no area covers nothing, but
      // saying so beats a 0 that looks like a measurement.
      out.mesh_completeness =
          MetricValue::missing(std::string("RUN/map/mesh.ply has no surface: ") + e.what());
      continue;
    }
    const std::vector<double> distances = mesh_true->distances(true_samples_W);
    const auto covered = std::count_if(distances.begin(), distances.end(), [&](double d) {
      return d <= completeness_distance_m;
    });
    out.mesh_completeness =
        MetricValue::of(static_cast<double>(covered) / static_cast<double>(distances.size()));
  }
  return metrics;
}

std::vector<MeshMetrics> measureRunMesh(const std::filesystem::path& mesh_path,
                                        const std::vector<MeshAlignment>& alignments,
                                        const std::filesystem::path& scene_path,
                                        const std::filesystem::path& reflectance_hdr,
                                        const MeshMetricsOptions& options) {
  options.validate();
  std::vector<MeshMetrics> metrics;
  std::error_code error;
  if (!std::filesystem::is_regular_file(mesh_path, error)) {
    for (std::size_t a = 0; a < alignments.size(); ++a) metrics.push_back(bothMissing(kNoMesh));
    return metrics;
  }
  // The alignments that exist, measured together; the others say why not.
  std::vector<Sim3> measurable;
  for (const MeshAlignment& alignment : alignments) {
    metrics.push_back(bothMissing(alignment.why_missing));
    if (alignment.S_true_est) measurable.push_back(*alignment.S_true_est);
  }
  if (measurable.empty()) return metrics;

  const PlyMesh mesh_est = readPly(mesh_path);
  if (mesh_est.vertices.empty()) {
    for (MeshMetrics& m : metrics) m = bothMissing("RUN/map/mesh.ply has no vertices");
    return metrics;
  }
  for (std::size_t i = 0; i < mesh_est.vertices.size(); ++i) {
    if (!mesh_est.vertices[i].allFinite()) {
      throw InputError(mesh_path, "vertex " + std::to_string(i),
                       "not finite: expected finite coordinates in W");
    }
  }

  const PlyMesh scene = readPly(scene_path);
  if (scene.triangles.empty()) {
    throw InputError(scene_path, "", "has no triangles: expected the true surface as a triangle mesh");
  }
  TrueSurfaceSamples samples;
  try {
    // Embree's BVH is freed before the distance trees are built (memory).
    const MeshRayCaster scene_caster(scene.vertices, scene.triangles);
    samples = sampleTrueSurface(scene_caster, reflectance_hdr, options.max_footprint_samples);
  } catch (const std::invalid_argument& e) {
    throw InputError(scene_path, "", std::string("not a usable true surface: ") + e.what());
  }
  std::vector<MeshMetrics> measured;
  try {
    measured = computeMeshMetrics(mesh_est, measurable, scene, samples.points_W,
                                  options.completeness_distance_m);
  } catch (const std::invalid_argument& e) {
    // Only the true scene can fail here (the produced mesh's vertices are
    // checked above and its failures become reasons): say which file.
    throw InputError(scene_path, "", std::string("not a usable true surface: ") + e.what());
  }
  std::size_t next = 0;
  for (std::size_t a = 0; a < alignments.size(); ++a) {
    if (!alignments[a].S_true_est) continue;
    metrics[a] = measured[next++];
    metrics[a].footprint_stride = samples.stride;
  }
  return metrics;
}

}  // namespace hsmap
