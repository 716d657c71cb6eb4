#pragma once
// The mesh metrics of metrics.json (DATASET.md, docs/EVALUATE.md): the
// produced surface RUN/map/mesh.ply against the true one truth/scene.ply.
//
// The produced mesh is in the run's W; the frames' similarity S_true_est
// (trajectory_metrics.h, the alignment of rgb_ate_aligned_m) maps it into the
// truth's W first, p_true = s R p_est + t, so that, like the trajectory's
// shape, the mesh's shape is judged beyond geo-referencing (no new fit: a
// mesh placed consistently with its own trajectory scores 0).
//
//   mesh_accuracy_m    median over the produced mesh's vertices v of
//                      dist(S v, true surface): how far the surface lies from
//                      the truth (the median, so that a few stray triangles
//                      at the mesh's edge do not dominate).
//   mesh_completeness  fraction of the true-surface samples (true_surface_samples.h:
//                      the true surface under the true ortho-image's footprint,
//                      on a regular lattice of at most max_footprint_samples)
//                      whose distance to the mapped produced mesh is
//                      <= completeness_distance_m (2 cm): how much of the seen
//                      seabed the mesh covers.
// Distances are point-to-triangle-mesh (nearest point of any triangle),
// through CGAL's AABB tree (triangle_mesh_distance.h).
//
// measureRunMesh() is the whole measurement on a run's files; a metric that
// cannot be measured is missing with the reason (no mesh.ply, no alignment,
// a mesh without vertices or triangles, an empty footprint).
//
// Several alignments at once. evaluate measures the mesh under the frames'
// Umeyama similarity (the contract's keys) and under the attitude-anchored
// one (trajectory_metrics.h; the extension keys *_attitude_aligned). The
// files are read, the true surface sampled and its distance tree built once;
// what is repeated per alignment is mapping the vertices, querying them, and
// building and querying the mapped mesh's tree.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/sim3.h"
#include "core/io/ply_io.h"
#include "pipelines/evaluate/metric_value.h"
#include "pipelines/evaluate/true_surface_samples.h"

namespace hsmap {

struct MeshMetricsOptions {
  // A true-surface sample counts as covered within this distance (DATASET.md: 2 cm).
  double completeness_distance_m = 0.02;
  // Bound on the true-surface samples (true_surface_samples.h); keeps a
  // 100 m transect's evaluation to seconds.
  std::int64_t max_footprint_samples = kDefaultMaxFootprintSamples;

  // std::invalid_argument naming the field unless completeness_distance_m is
  // finite and > 0 and max_footprint_samples > 0.
  void validate() const;
};

struct MeshMetrics {
  MetricValue mesh_accuracy_m;
  MetricValue mesh_completeness;
  int footprint_stride = 0;  // lattice stride of the samples (0 when not sampled)
};

// One way of placing the produced mesh in the truth's W: the similarity
// S_true_est, or the reason there is none.
struct MeshAlignment {
  std::optional<Sim3> S_true_est;
  std::string why_missing;  // used when S_true_est is absent
};

// On loaded data, one MeshMetrics per alignment (in their order).
// `true_scene` is truth/scene.ply in the truth's W, `true_samples_W` the
// footprint samples. The distance trees of the true scene and of each mapped
// mesh are built one after the other, never two at once (a 100 m transect's
// scene has millions of triangles). Throws std::invalid_argument when the
// mesh has no vertices or the true scene no triangle with an area
// (TriangleMeshDistance).
std::vector<MeshMetrics> computeMeshMetrics(const PlyMesh& mesh_est,
                                            const std::vector<Sim3>& alignments,
                                            const PlyMesh& true_scene,
                                            const std::vector<Eigen::Vector3d>& true_samples_W,
                                            double completeness_distance_m);

// On a run's files, one MeshMetrics per alignment (in their order); an
// alignment without a similarity gives both metrics missing with its reason.
// Reads the true scene and reflectance only when mesh_path exists and some
// alignment has a similarity. Throws InputError for a malformed mesh.ply
// (readPly), a non-finite vertex, a true scene without triangles or a
// reflectance raster without a local map info.
std::vector<MeshMetrics> measureRunMesh(const std::filesystem::path& mesh_path,
                                        const std::vector<MeshAlignment>& alignments,
                                        const std::filesystem::path& scene_path,
                                        const std::filesystem::path& reflectance_hdr,
                                        const MeshMetricsOptions& options = {});

}  // namespace hsmap
