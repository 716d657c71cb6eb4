#include "pipelines/surface/mesh_cleaning.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>

#include "pipelines/surface/surface_reconstruction.h"
#include "tests/pipelines/surface/synthetic_scenes.h"

namespace hsmap {
namespace {

constexpr double kSpacing = 0.015;  // 1.5 cm, dense seabed points at 2 m altitude

// A height-field sheet z = height(x, y) (+ noise of `noise_std`) on an
// nx x ny grid from (x0, y0), triangles CCW seen from +z (outward = up
// here). point_index = 1000 + vertex so that it differs from the index.
struct Sheet {
  SurfaceMesh mesh;
  int nx = 0, ny = 0;
  int vertex(int i, int j) const { return j * nx + i; }
  bool onBorder(int v) const {
    const int i = v % nx, j = v / nx;
    return i == 0 || j == 0 || i == nx - 1 || j == ny - 1;
  }
};

Sheet makeSheet(int nx, int ny, double x0, double y0,
                const std::function<double(double, double)>& height, double noise_std = 0.0,
                unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_std > 0.0 ? noise_std : 1.0);
  Sheet s;
  s.nx = nx;
  s.ny = ny;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = x0 + i * kSpacing, y = y0 + j * kSpacing;
      s.mesh.vertices.emplace_back(x, y, height(x, y) + (noise_std > 0.0 ? noise(rng) : 0.0));
      s.mesh.point_index.push_back(1000 + int(s.mesh.point_index.size()));
    }
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      s.mesh.triangles.emplace_back(s.vertex(i, j), s.vertex(i + 1, j), s.vertex(i + 1, j + 1));
      s.mesh.triangles.emplace_back(s.vertex(i, j), s.vertex(i + 1, j + 1), s.vertex(i, j + 1));
    }
  return s;
}

double flat(double, double) { return 0.0; }

// Appends `part` to `mesh` (vertices, triangles, point_index offset by the
// vertices already there).
void append(SurfaceMesh& mesh, const SurfaceMesh& part) {
  const int offset = int(mesh.vertices.size());
  for (std::size_t v = 0; v < part.vertices.size(); ++v) {
    mesh.vertices.push_back(part.vertices[v]);
    mesh.point_index.push_back(part.point_index[v] + offset);
  }
  for (const auto& t : part.triangles)
    mesh.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
}

Eigen::Vector3d normalOf(const SurfaceMesh& mesh, const Eigen::Vector3i& t) {
  return (mesh.vertices[t[1]] - mesh.vertices[t[0]])
      .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
}

// A triangle named by its vertices' point indices, as a sorted triple.
std::array<int, 3> key(const SurfaceMesh& mesh, const Eigen::Vector3i& t) {
  std::array<int, 3> k = {mesh.point_index[t[0]], mesh.point_index[t[1]], mesh.point_index[t[2]]};
  std::sort(k.begin(), k.end());
  return k;
}

// Checks that every output triangle is an input triangle (by point
// indices) whose normal still points the way the input's did, and that
// every output vertex carries the point_index of an input vertex within
// `max_move` of it. Returns the input triangles kept.
std::set<std::array<int, 3>> checkKeptFromInput(const SurfaceMesh& in, const SurfaceMesh& out,
                                                double max_move) {
  std::map<std::array<int, 3>, Eigen::Vector3d> input_normals;
  for (const auto& t : in.triangles) input_normals[key(in, t)] = normalOf(in, t);
  std::map<int, Eigen::Vector3d> input_positions;
  for (std::size_t v = 0; v < in.vertices.size(); ++v)
    input_positions[in.point_index[v]] = in.vertices[v];
  EXPECT_EQ(out.vertices.size(), out.point_index.size());
  for (std::size_t v = 0; v < out.vertices.size(); ++v) {
    const auto it = input_positions.find(out.point_index[v]);
    EXPECT_NE(it, input_positions.end());
    if (it != input_positions.end()) {
      EXPECT_LE((out.vertices[v] - it->second).norm(), max_move) << "vertex " << v;
    }
  }
  std::set<std::array<int, 3>> kept;
  for (const auto& t : out.triangles) {
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(t[k] >= 0 && t[k] < int(out.vertices.size()));
    const auto it = input_normals.find(key(out, t));
    EXPECT_NE(it, input_normals.end());
    if (it == input_normals.end()) continue;
    EXPECT_GT(normalOf(out, t).dot(it->second), 0.0) << "a triangle changed orientation";
    kept.insert(it->first);
  }
  return kept;
}

TEST(MeshCleaning, RemovesAFloatingPatchAndKeepsTheWholeSheet) {
  // A 1 m x 1 m seabed sheet with 1 mm noise and a 3 x 3 floating patch
  // 30 cm above it (an outlier cluster).
  const Sheet sheet = makeSheet(67, 67, 0.0, 0.0, flat, 0.001);
  const Sheet patch = makeSheet(3, 3, 0.4, 0.4, [](double, double) { return 0.3; });
  SurfaceMesh mesh = sheet.mesh;
  append(mesh, patch.mesh);
  MeshCleaningReport report;
  const SurfaceMesh out = cleanMesh(mesh, MeshCleaningOptions(), &report);
  const auto kept = checkKeptFromInput(mesh, out, 0.003);
  EXPECT_EQ(kept.size(), sheet.mesh.triangles.size());
  EXPECT_EQ(out.triangles.size(), sheet.mesh.triangles.size());
  EXPECT_EQ(out.vertices.size(), sheet.mesh.vertices.size());
  for (const int p : out.point_index) EXPECT_LT(p, 1000 + int(sheet.mesh.vertices.size()));
  EXPECT_EQ(report.components_removed, 1);
  EXPECT_EQ(report.component_triangles, 8);
  EXPECT_EQ(report.vertices_removed, 9);
  EXPECT_EQ(report.long_edge_triangles, 0);
  EXPECT_EQ(report.spikes, 0);
  EXPECT_NEAR(report.median_edge_m, kSpacing, 0.002);
}

TEST(MeshCleaning, RemovesLongTrianglesAcrossTheRim) {
  // A fan of thin triangles from a point 50 cm beyond the sheet's left rim
  // to the rim's vertices, as the Delaunay joins far points on the hull.
  const Sheet sheet = makeSheet(40, 40, 0.0, 0.0, flat, 0.001);
  SurfaceMesh mesh = sheet.mesh;
  const int far = int(mesh.vertices.size());
  mesh.vertices.emplace_back(-0.5, 0.3, 0.0);
  mesh.point_index.push_back(5000);
  for (int j = 0; j + 1 < sheet.ny; ++j) {
    Eigen::Vector3i t(far, sheet.vertex(0, j + 1), sheet.vertex(0, j));
    if (normalOf(mesh, t).z() < 0.0) std::swap(t[1], t[2]);
    mesh.triangles.push_back(t);
  }
  MeshCleaningReport report;
  const SurfaceMesh out = cleanMesh(mesh, MeshCleaningOptions(), &report);
  const auto kept = checkKeptFromInput(mesh, out, 0.003);
  EXPECT_EQ(report.long_edge_triangles, sheet.ny - 1);
  EXPECT_EQ(kept.size(), sheet.mesh.triangles.size());
  EXPECT_EQ(out.triangles.size(), sheet.mesh.triangles.size());
  EXPECT_EQ(report.vertices_removed, 1);
  EXPECT_EQ(std::count(out.point_index.begin(), out.point_index.end(), 5000), 0);
}

TEST(MeshCleaning, AbsoluteEdgeCapRemovesTrianglesTheRelativeTestKeeps) {
  const Sheet sheet = makeSheet(10, 10, 0.0, 0.0, flat);
  MeshCleaningOptions options;
  options.max_edge_m = 0.02;  // the 2.1 cm diagonals go, the 1.5 cm sides would stay
  MeshCleaningReport report;
  const SurfaceMesh out = cleanMesh(sheet.mesh, options, &report);
  EXPECT_TRUE(out.triangles.empty());
  EXPECT_EQ(report.long_edge_triangles, static_cast<long long>(sheet.mesh.triangles.size()));
}

TEST(MeshCleaning, FlattensSpikesOntoTheirNeighboursPlane) {
  // A tilted plane with one vertex pulled 10 cm out (towards the cameras)
  // and one pushed 10 cm in.
  auto plane = [](double x, double y) { return 0.1 * x - 0.05 * y + 0.2; };
  Sheet sheet = makeSheet(30, 30, 0.0, 0.0, plane, 0.001);
  const int up = sheet.vertex(10, 12), down = sheet.vertex(20, 17);
  sheet.mesh.vertices[up].z() += 0.10;
  sheet.mesh.vertices[down].z() -= 0.10;
  MeshCleaningOptions options;
  options.smoothing_iterations = 0;
  MeshCleaningReport report;
  const SurfaceMesh out = cleanMesh(sheet.mesh, options, &report);
  EXPECT_EQ(report.spikes, 2);
  EXPECT_EQ(out.triangles.size(), sheet.mesh.triangles.size());
  checkKeptFromInput(sheet.mesh, out, 0.11);
  const Eigen::Vector3d normal = Eigen::Vector3d(-0.1, 0.05, 1.0).normalized();
  for (const int v : {up, down}) {
    const auto it = std::find(out.point_index.begin(), out.point_index.end(), 1000 + v);
    ASSERT_NE(it, out.point_index.end());
    const Eigen::Vector3d& p = out.vertices[it - out.point_index.begin()];
    const double distance =
        std::abs(normal.dot(p - Eigen::Vector3d(p.x(), p.y(), plane(p.x(), p.y()))));
    EXPECT_LT(distance, 0.001) << "spike " << v;
    // Moved onto the plane inside its one-ring, not across the surface
    // (the spike was pulled vertically, the plane's normal is 6 deg off).
    EXPECT_LT((p - sheet.mesh.vertices[v]).cross(normal).norm(), kSpacing) << "spike " << v;
  }
  // Nothing else moves (1 mm of noise is no spike).
  for (std::size_t v = 0; v < out.vertices.size(); ++v) {
    const int input = out.point_index[v] - 1000;
    if (input != up && input != down) {
      EXPECT_EQ(out.vertices[v], sheet.mesh.vertices[input]);
    }
  }
}

TEST(MeshCleaning, SmoothingRemovesNoiseButNotRelief) {
  // A Gaussian bump (10 cm high, sigma 30 cm) on 1.5 cm spacing.
  auto bump = [](double x, double y) { return 0.1 * std::exp(-(x * x + y * y) / (2 * 0.3 * 0.3)); };
  const int n = 121;  // +-0.9 m
  const double x0 = -0.9;
  const Sheet noisy = makeSheet(n, n, x0, x0, bump, 0.001, 7);
  const Sheet clean = makeSheet(n, n, x0, x0, bump);
  MeshCleaningReport report;
  const SurfaceMesh out = cleanMesh(noisy.mesh, MeshCleaningOptions(), &report);
  const SurfaceMesh out_clean = cleanMesh(clean.mesh, MeshCleaningOptions());
  ASSERT_EQ(out.vertices.size(), noisy.mesh.vertices.size());
  ASSERT_EQ(out_clean.vertices.size(), clean.mesh.vertices.size());
  checkKeptFromInput(noisy.mesh, out, 0.003);
  EXPECT_EQ(out.triangles.size(), noisy.mesh.triangles.size());
  EXPECT_EQ(report.spikes, 0);

  // Vertical distance to the true surface (the bump's slope is <= 0.2, so
  // within 2 % of the distance along the normal).
  double in_sq = 0.0, out_sq = 0.0, peak_shift_noisy = 0.0;
  int interior = 0, near_peak = 0;
  for (std::size_t v = 0; v < out.vertices.size(); ++v) {
    const int input = out.point_index[v] - 1000;
    ASSERT_EQ(out.point_index[v], noisy.mesh.point_index[input]);
    const Eigen::Vector3d& p = out.vertices[v];
    if (noisy.onBorder(input)) {
      EXPECT_EQ(p, noisy.mesh.vertices[input]) << "border vertex moved";
      continue;
    }
    const Eigen::Vector3d& q = noisy.mesh.vertices[input];
    in_sq += std::pow(q.z() - bump(q.x(), q.y()), 2);
    out_sq += std::pow(p.z() - bump(p.x(), p.y()), 2);
    ++interior;
    if (p.head<2>().norm() < 0.05) {
      peak_shift_noisy += p.z() - bump(p.x(), p.y());
      ++near_peak;
    }
  }
  const double rms_in = std::sqrt(in_sq / interior), rms_out = std::sqrt(out_sq / interior);
  peak_shift_noisy /= near_peak;
  // Without noise, how far the peak vertex moves is the smoothing's bias.
  const int peak = clean.vertex(n / 2, n / 2);
  const auto it =
      std::find(out_clean.point_index.begin(), out_clean.point_index.end(), 1000 + peak);
  ASSERT_NE(it, out_clean.point_index.end());
  const double peak_shift =
      out_clean.vertices[it - out_clean.point_index.begin()].z() - bump(0.0, 0.0);
  RecordProperty("rms_in_mm", std::to_string(rms_in * 1e3));
  RecordProperty("rms_out_mm", std::to_string(rms_out * 1e3));
  RecordProperty("peak_shift_mm", std::to_string(peak_shift * 1e3));
  std::printf(
      "bump: rms to the true surface %.3f mm -> %.3f mm; peak moved %.4f mm (noise-free), "
      "mean shift within 5 cm of the peak %.4f mm (noisy); %.3f s\n",
      rms_in * 1e3, rms_out * 1e3, peak_shift * 1e3, peak_shift_noisy * 1e3, report.seconds);
  EXPECT_NEAR(rms_in, 0.001, 0.0001);
  EXPECT_LT(rms_out, 0.8 * rms_in);
  EXPECT_LT(std::abs(peak_shift), 0.001);
  EXPECT_LT(std::abs(peak_shift_noisy), 0.001);
}

TEST(MeshCleaning, KeepsPointIndexAndPositionsWithEverythingOff) {
  const Sheet sheet = makeSheet(12, 9, 0.0, 0.0, flat, 0.001);
  MeshCleaningOptions off;
  off.max_edge_factor = 0.0;
  off.min_component_fraction = 0.0;
  off.spike_factor = 0.0;
  off.smoothing_iterations = 0;
  const SurfaceMesh out = cleanMesh(sheet.mesh, off);
  EXPECT_EQ(out.vertices, sheet.mesh.vertices);
  EXPECT_EQ(out.point_index, sheet.mesh.point_index);
  EXPECT_EQ(checkKeptFromInput(sheet.mesh, out, 0.0).size(), sheet.mesh.triangles.size());
}

TEST(MeshCleaning, SplitsNonManifoldPlacesWithoutFlippingATriangle) {
  MeshCleaningOptions options;
  options.min_component_fraction = 0.0;
  options.smoothing_iterations = 0;
  // Two sheets touching at one corner vertex (a pinched vertex) ...
  Sheet a = makeSheet(5, 5, 0.0, 0.0, flat);
  const Sheet b = makeSheet(5, 5, 4 * kSpacing, 4 * kSpacing, flat);
  SurfaceMesh mesh = a.mesh;
  append(mesh, b.mesh);
  const int corner_a = a.vertex(4, 4), corner_b = int(a.mesh.vertices.size()) + b.vertex(0, 0);
  for (auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] == corner_b) t[k] = corner_a;
  // ... a fin of two triangles standing on an interior edge of the first
  // sheet, so that the edge has four triangles ...
  const int e0 = a.vertex(1, 1), e1 = a.vertex(2, 1);
  const int top = int(mesh.vertices.size());
  mesh.vertices.emplace_back(1.5 * kSpacing, 1.2 * kSpacing, 0.01);
  mesh.vertices.emplace_back(1.5 * kSpacing, 0.8 * kSpacing, 0.01);
  mesh.point_index.push_back(9000);
  mesh.point_index.push_back(9002);
  mesh.triangles.emplace_back(e0, e1, top);
  mesh.triangles.emplace_back(e1, e0, top + 1);
  // ... and a flipped triangle on the first sheet's rim, facing down: it
  // runs along the rim edge in the same direction as the sheet's triangle
  // there, so one of the two has the wrong orientation; which one is not
  // known, both go.
  const int r0 = a.vertex(1, 0), r1 = a.vertex(2, 0);
  const int below = int(mesh.vertices.size());
  mesh.vertices.emplace_back(1.5 * kSpacing, -1.0 * kSpacing, 0.0);
  mesh.point_index.push_back(9001);
  mesh.triangles.emplace_back(r0, r1, below);
  MeshCleaningReport report;
  SurfaceMesh out;
  ASSERT_NO_THROW(out = cleanMesh(mesh, options, &report));
  EXPECT_EQ(report.non_manifold_edges, 1);
  EXPECT_GE(report.duplicated_vertices, 3);  // the pinched vertex, the four-triangle edge's ends
  EXPECT_EQ(report.inconsistent_triangles, 2);
  EXPECT_EQ(out.triangles.size(), mesh.triangles.size() - 2);
  checkKeptFromInput(mesh, out, 0.0);
  // The pinched vertex comes out twice, both copies with its point index.
  EXPECT_EQ(std::count(out.point_index.begin(), out.point_index.end(), mesh.point_index[corner_a]),
            2);
  EXPECT_EQ(std::count(out.point_index.begin(), out.point_index.end(), 9000), 1);
}

TEST(MeshCleaning, SplitsAnEdgeOfFourTriangles) {
  // Two tents sharing their ridge edge: four triangles on one edge, as
  // where two matter cells of the graph cut touch along an edge.
  SurfaceMesh mesh;
  mesh.vertices = {{0, 0, 0},
                   {0.02, 0, 0},
                   {0.01, 0.01, 0.005},
                   {0.01, -0.01, 0.005},
                   {0.01, 0.01, -0.005},
                   {0.01, -0.01, -0.005}};
  mesh.point_index = {0, 1, 2, 3, 4, 5};
  mesh.triangles = {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}, {0, 1, 5}};
  MeshCleaningOptions options;
  options.min_component_fraction = 0.0;
  options.smoothing_iterations = 0;
  options.spike_factor = 0.0;
  MeshCleaningReport report;
  SurfaceMesh out;
  ASSERT_NO_THROW(out = cleanMesh(mesh, options, &report));
  EXPECT_EQ(report.non_manifold_edges, 1);
  EXPECT_GE(report.duplicated_vertices, 2);
  EXPECT_EQ(out.triangles.size(), 4u);
  EXPECT_EQ(checkKeptFromInput(mesh, out, 0.0).size(), 4u);
}

TEST(MeshCleaning, CleansAGraphCutSeabedKeepingItsOrientation) {
  // The surface stage's own output: a noisy seabed with a bump from random
  // points (irregular triangles, slivers), plus a cluster of outliers
  // floating 30 cm above it.
  auto field = [](double x, double y) {
    return 0.2 * std::exp(-(x * x + y * y) / (2.0 * 0.4 * 0.4));
  };
  std::vector<Eigen::Vector3d> cameras;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) cameras.emplace_back(-2.0 + 0.8 * i, -2.0 + 0.8 * j, 2.5);
  VisibilityPoints points = surface_test::sampleHeightField(field, 2.0, 6000, 0.002, cameras, 5);
  std::mt19937 rng(3);
  std::normal_distribution<double> cluster(0.0, 0.02);
  for (int k = 0; k < 12; ++k) {
    points.p_W.emplace_back(1.0 + cluster(rng), 1.0 + cluster(rng), 0.3 + cluster(rng));
    points.views.push_back({0, 7, 14, 21});
  }
  const SurfaceMesh mesh = reconstructSurface(points).mesh;
  ASSERT_GT(mesh.triangles.size(), 5000u);
  MeshCleaningReport report;
  const SurfaceMesh out = cleanMesh(mesh, MeshCleaningOptions(), &report);
  std::printf(
      "graph-cut seabed: %lld -> %lld triangles: %lld long-edge, %lld in %lld small components, "
      "%lld spikes, %lld non-manifold edges, %lld vertex copies, %lld inconsistent, "
      "%lld smoothing rejected; median edge %.1f mm; %.3f s\n",
      report.input_triangles, report.output_triangles, report.long_edge_triangles,
      report.component_triangles, report.components_removed, report.spikes,
      report.non_manifold_edges, report.duplicated_vertices, report.inconsistent_triangles,
      report.smoothing_rejected, report.median_edge_m * 1e3, report.seconds);
  const auto kept = checkKeptFromInput(mesh, out, 0.5 * report.median_edge_m + 1e-9);
  EXPECT_EQ(kept.size(), out.triangles.size());
  EXPECT_GT(out.triangles.size(), 0.9 * mesh.triangles.size());
  for (const auto& p : out.vertices) EXPECT_TRUE(p.allFinite());
  // Nothing is left floating above the seabed, and every edge has one or
  // two triangles.
  for (int t = 0; t < int(out.triangles.size()); ++t) {
    const Eigen::Vector3d c = surface_test::triangleCentroid(out, t);
    EXPECT_LT(c.z(), field(c.x(), c.y()) + 0.05) << "triangle " << t;
  }
  std::map<std::pair<int, int>, int> edge_use;
  for (const auto& t : out.triangles)
    for (int k = 0; k < 3; ++k) ++edge_use[std::minmax(t[k], t[(k + 1) % 3])];
  for (const auto& [edge, uses] : edge_use) EXPECT_LE(uses, 2);
}

TEST(MeshCleaning, ValidateSaysWhatIsWrong) {
  EXPECT_EQ(MeshCleaningOptions().validate(), "");
  auto with = [](const std::function<void(MeshCleaningOptions&)>& change) {
    MeshCleaningOptions o;
    change(o);
    return o.validate();
  };
  EXPECT_EQ(with([](auto& o) { o.max_edge_factor = -1.0; }),
            "max_edge_factor must be finite and >= 0 (0 = no relative edge limit)");
  EXPECT_EQ(with([](auto& o) { o.max_edge_factor = 0.5; }),
            "max_edge_factor must be 0 (off) or >= 1 (below 1 it removes most of the mesh)");
  EXPECT_EQ(with([](auto& o) { o.max_edge_m = NAN; }),
            "max_edge_m must be finite and >= 0 (metres; 0 = no absolute edge limit)");
  EXPECT_EQ(with([](auto& o) { o.min_component_fraction = 1.5; }),
            "min_component_fraction must be in [0, 1]");
  EXPECT_EQ(with([](auto& o) { o.spike_factor = -0.1; }),
            "spike_factor must be finite and >= 0 (0 = no spike removal)");
  EXPECT_EQ(with([](auto& o) { o.smoothing_iterations = -1; }),
            "smoothing_iterations must be >= 0 (0 = no smoothing)");
  EXPECT_EQ(with([](auto& o) { o.smoothing_step = 0.0; }),
            "smoothing_step must be finite and > 0 (in squared median edge lengths)");
  MeshCleaningOptions bad;
  bad.smoothing_iterations = -1;
  EXPECT_THROW(cleanMesh(SurfaceMesh(), bad), std::invalid_argument);
}

TEST(MeshCleaning, EmptyMeshStaysEmpty) {
  MeshCleaningReport report;
  const SurfaceMesh out = cleanMesh(SurfaceMesh(), MeshCleaningOptions(), &report);
  EXPECT_TRUE(out.vertices.empty());
  EXPECT_TRUE(out.triangles.empty());
  EXPECT_TRUE(out.point_index.empty());
  EXPECT_EQ(report.output_triangles, 0);
}

}  // namespace
}  // namespace hsmap
