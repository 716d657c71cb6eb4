#include "core/util/median.h"
#include "pipelines/surface/mesh_cleaning.h"

#include <CGAL/Eigen_matrix.h>
#include <CGAL/Eigen_solver_traits.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/smooth_shape.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

namespace hsmap {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VertexIndex = Mesh::Vertex_index;
using FaceIndex = Mesh::Face_index;
using Triangle = std::array<std::size_t, 3>;

// Jacobi preconditioning under its own name: CGAL's Eigen_solver_traits
// specialises BiCGSTAB with Eigen's default (diagonal) preconditioner without
// the factor() that smooth_shape needs.
struct JacobiPreconditioner : Eigen::DiagonalPreconditioner<double> {
  using Eigen::DiagonalPreconditioner<double>::DiagonalPreconditioner;
};

Eigen::Vector3d toEigen(const Point& p) { return {p.x(), p.y(), p.z()}; }

// Triangles incident to each vertex, compressed rows.
struct Incidence {
  std::vector<std::size_t> first, triangle;
  Incidence(std::size_t n_vertices, const std::vector<Triangle>& triangles)
      : first(n_vertices + 1, 0) {
    for (const Triangle& t : triangles)
      for (const std::size_t v : t) ++first[v + 1];
    for (std::size_t v = 0; v < n_vertices; ++v) first[v + 1] += first[v];
    triangle.resize(first.back());
    std::vector<std::size_t> fill(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t < triangles.size(); ++t)
      for (const std::size_t v : triangles[t]) triangle[fill[v]++] = t;
  }
};

// One incident triangle of a vertex v seen across its edge to neighbour w:
// `out` when the triangle runs v -> w, otherwise w -> v.
struct Wing {
  std::size_t neighbour, slot;  // slot: position among v's incident triangles
  bool out;
  bool operator<(const Wing& o) const { return neighbour < o.neighbour; }
};

void wingsOf(std::size_t v, const Incidence& incidence, const std::vector<Triangle>& triangles,
             std::vector<Wing>& wings) {
  wings.clear();
  for (std::size_t i = incidence.first[v]; i < incidence.first[v + 1]; ++i) {
    const Triangle& t = triangles[incidence.triangle[i]];
    const int k = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
    const std::size_t slot = i - incidence.first[v];
    wings.push_back({t[(k + 1) % 3], slot, true});
    wings.push_back({t[(k + 2) % 3], slot, false});
  }
  std::sort(wings.begin(), wings.end());
}

std::size_t findRoot(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Step 3: makes the soup an oriented 2-manifold without reversing any
// triangle, as CGAL's orient_polygon_soup does (Gueziec et al. 2001) but
// in linear time on flat arrays (orient_polygon_soup's maps and sets took
// 1.7 s on 530 000 triangles, 40 % of the whole cleaning then):
//  - two triangles on one edge in the same direction (one of them has the
//    wrong orientation, which one is not known) are both dropped, until no
//    such pair is left;
//  - around each vertex, its triangles are grouped in fans, joined across
//    the edges shared by exactly two triangles in opposite directions; a
//    vertex of more than one fan (pinched, or on an edge of more than two
//    triangles) gets one copy per extra fan.
// `triangles` is rewritten on the copies; returns, per vertex of the
// result, the input vertex it copies.
std::vector<std::size_t> makeManifold(std::vector<Triangle>& triangles, std::size_t n_vertices,
                                      MeshCleaningReport& r) {
  std::vector<Wing> wings;
  for (bool changed = true; changed;) {
    changed = false;
    const Incidence incidence(n_vertices, triangles);
    std::vector<char> drop(triangles.size(), 0);
    for (std::size_t v = 0; v < n_vertices; ++v) {
      wingsOf(v, incidence, triangles, wings);
      for (std::size_t i = 0; i < wings.size();) {
        std::size_t j = i + 1;
        while (j < wings.size() && wings[j].neighbour == wings[i].neighbour) ++j;
        if (j - i == 2 && wings[i].out == wings[i + 1].out) {
          drop[incidence.triangle[incidence.first[v] + wings[i].slot]] = 1;
          drop[incidence.triangle[incidence.first[v] + wings[i + 1].slot]] = 1;
        }
        i = j;
      }
    }
    const std::size_t before = triangles.size();
    std::size_t kept = 0;
    for (std::size_t t = 0; t < triangles.size(); ++t)
      if (!drop[t]) triangles[kept++] = triangles[t];
    triangles.resize(kept);
    r.inconsistent_triangles += static_cast<long long>(before - kept);
    changed = kept != before;
  }

  const Incidence incidence(n_vertices, triangles);
  std::vector<std::size_t> origin(n_vertices);
  std::iota(origin.begin(), origin.end(), std::size_t(0));
  std::vector<Triangle> split = triangles;
  std::vector<std::size_t> parent, fan_vertex;
  for (std::size_t v = 0; v < n_vertices; ++v) {
    const std::size_t degree = incidence.first[v + 1] - incidence.first[v];
    if (degree < 2) continue;
    wingsOf(v, incidence, triangles, wings);
    parent.resize(degree);
    std::iota(parent.begin(), parent.end(), std::size_t(0));
    for (std::size_t i = 0; i < wings.size();) {
      std::size_t j = i + 1;
      while (j < wings.size() && wings[j].neighbour == wings[i].neighbour) ++j;
      if (j - i == 2 && wings[i].out != wings[i + 1].out)
        parent[findRoot(parent, wings[i].slot)] = findRoot(parent, wings[i + 1].slot);
      if (j - i > 2 && v < wings[i].neighbour) ++r.non_manifold_edges;
      i = j;
    }
    fan_vertex.assign(degree, SIZE_MAX);
    fan_vertex[findRoot(parent, 0)] = v;  // the first fan keeps the vertex
    for (std::size_t slot = 0; slot < degree; ++slot) {
      std::size_t& copy = fan_vertex[findRoot(parent, slot)];
      if (copy == SIZE_MAX) {
        copy = origin.size();
        origin.push_back(v);
      }
      if (copy == v) continue;
      Triangle& t = split[incidence.triangle[incidence.first[v] + slot]];
      for (std::size_t& corner : t)
        if (corner == v) corner = copy;
    }
  }
  triangles = std::move(split);
  r.duplicated_vertices = static_cast<long long>(origin.size() - n_vertices);
  return origin;
}

// Least-squares plane of `points`: centroid and unit normal (the
// eigenvector of the smallest eigenvalue of their scatter). False when the
// points are (nearly) collinear, relative to `scale`.
bool fitPlane(const std::vector<Eigen::Vector3d>& points, double scale, Eigen::Vector3d* centroid,
              Eigen::Vector3d* normal) {
  if (points.size() < 3) return false;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : points) c += p;
  c /= double(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) scatter += (p - c) * (p - c).transpose();
  scatter /= double(points.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  // The middle eigenvalue is the squared spread across the best line.
  if (!(eig.eigenvalues()(1) > 1e-4 * scale * scale)) return false;
  *centroid = c;
  *normal = eig.eigenvectors().col(0);
  return true;
}

// Step 1: moves spikes onto the plane of their one-ring neighbours, on the soup
// (before the long-edge test, which would otherwise cut a spike's long
// edges and leave a hole), in passes until none is left (two spikes side by
// side: the first flattened makes the second's plane right). Returns the
// vertices moved.
long long flattenSpikes(std::vector<Eigen::Vector3d>& positions,
                        const std::vector<Triangle>& triangles, double spike_factor) {
  const std::size_t n = positions.size();
  const Incidence incidence(n, triangles);
  const std::vector<std::size_t>& first = incidence.first;
  const std::vector<std::size_t>& incident = incidence.triangle;

  std::vector<char> moved(n, 0);
  std::vector<std::size_t> ring_ids;
  std::vector<Eigen::Vector3d> ring;
  std::vector<std::pair<std::size_t, std::size_t>> opposite_edges;
  for (int pass = 0; pass < 3; ++pass) {
    long long in_pass = 0;
    for (std::size_t v = 0; v < n; ++v) {
      if (first[v] == first[v + 1]) continue;
      const Eigen::Vector3d p = positions[v];
      ring_ids.clear();
      opposite_edges.clear();
      for (std::size_t i = first[v]; i < first[v + 1]; ++i) {
        const Triangle& t = triangles[incident[i]];
        const int k = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
        opposite_edges.emplace_back(t[(k + 1) % 3], t[(k + 2) % 3]);
        ring_ids.push_back(t[(k + 1) % 3]);
        ring_ids.push_back(t[(k + 2) % 3]);
      }
      std::sort(ring_ids.begin(), ring_ids.end());
      ring_ids.erase(std::unique(ring_ids.begin(), ring_ids.end()), ring_ids.end());
      ring.clear();
      double edge_sum = 0.0;
      for (const std::size_t w : ring_ids) {
        ring.push_back(positions[w]);
        edge_sum += (positions[w] - p).norm();
      }
      const double mean_edge = edge_sum / double(ring.size());
      Eigen::Vector3d centroid, normal;
      if (!fitPlane(ring, mean_edge, &centroid, &normal)) continue;
      double distance = normal.dot(p - centroid);
      if (!(std::abs(distance) > spike_factor * mean_edge)) continue;
      // Orient the plane's normal like the vertex's faces (a spike's faces
      // all lean the same side of it, up or down), to check that the move
      // folds none of them.
      Eigen::Vector3d face_sum = Eigen::Vector3d::Zero();
      for (const auto& [a, b] : opposite_edges)
        face_sum += (positions[a] - p).cross(positions[b] - p);
      if (face_sum.dot(normal) < 0.0) {
        normal = -normal;
        distance = -distance;
      }
      auto folds = [&](const Eigen::Vector3d& q) {
        for (const auto& [a, b] : opposite_edges)
          if (!((positions[a] - q).cross(positions[b] - q).dot(normal) > 0.0)) return true;
        return false;
      };
      Eigen::Vector3d target = p - distance * normal;  // onto the plane, least motion
      if (folds(target)) target = centroid;            // on the plane too, inside the ring
      if (folds(target)) continue;
      positions[v] = target;
      if (!moved[v]) {
        moved[v] = 1;
        ++in_pass;
      }
    }
    if (in_pass == 0) break;
  }
  return std::count(moved.begin(), moved.end(), char(1));
}

}  // namespace

std::string MeshCleaningOptions::validate() const {
  if (!(max_edge_factor >= 0.0 && std::isfinite(max_edge_factor)))
    return "max_edge_factor must be finite and >= 0 (0 = no relative edge limit)";
  if (max_edge_factor > 0.0 && max_edge_factor < 1.0)
    return "max_edge_factor must be 0 (off) or >= 1 (below 1 it removes most of the mesh)";
  if (!(max_edge_m >= 0.0 && std::isfinite(max_edge_m)))
    return "max_edge_m must be finite and >= 0 (metres; 0 = no absolute edge limit)";
  if (!(min_component_fraction >= 0.0 && min_component_fraction <= 1.0))
    return "min_component_fraction must be in [0, 1]";
  if (!(spike_factor >= 0.0 && std::isfinite(spike_factor)))
    return "spike_factor must be finite and >= 0 (0 = no spike removal)";
  if (smoothing_iterations < 0) return "smoothing_iterations must be >= 0 (0 = no smoothing)";
  if (!(smoothing_step > 0.0 && std::isfinite(smoothing_step)))
    return "smoothing_step must be finite and > 0 (in squared median edge lengths)";
  return {};
}

SurfaceMesh cleanMesh(const SurfaceMesh& input, const MeshCleaningOptions& options,
                      MeshCleaningReport* report) {
  if (const std::string problem = options.validate(); !problem.empty())
    throw std::invalid_argument("mesh cleaning: options: " + problem);
  const auto start = std::chrono::steady_clock::now();
  MeshCleaningReport r;
  r.input_triangles = static_cast<long long>(input.triangles.size());
  const std::size_t n_vertices = input.vertices.size();

  // Valid triangles and the median edge length.
  std::vector<Triangle> triangles;
  triangles.reserve(input.triangles.size());
  for (const Eigen::Vector3i& t : input.triangles) {
    bool valid = t[0] != t[1] && t[1] != t[2] && t[2] != t[0];
    for (int k = 0; k < 3; ++k) valid = valid && t[k] >= 0 && std::size_t(t[k]) < n_vertices;
    if (!valid) {
      ++r.invalid_triangles;
      continue;
    }
    triangles.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  }
  std::vector<Eigen::Vector3d> positions = input.vertices;
  auto longestEdge = [&](const Triangle& t) {
    double longest = 0.0;
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (positions[t[k]] - positions[t[(k + 1) % 3]]).norm());
    return longest;
  };
  if (!triangles.empty()) {
    std::vector<double> lengths;
    lengths.reserve(3 * triangles.size());
    for (const Triangle& t : triangles)
      for (int k = 0; k < 3; ++k)
        lengths.push_back((input.vertices[t[k]] - input.vertices[t[(k + 1) % 3]]).norm());
    r.median_edge_m = upperMedian(std::move(lengths));
  }

  // 1. Spikes, first: the long-edge test would cut a spike's edges out.
  if (options.spike_factor > 0.0)
    r.spikes = flattenSpikes(positions, triangles, options.spike_factor);

  // 2. Long edges.
  double max_edge = std::numeric_limits<double>::infinity();
  if (options.max_edge_factor > 0.0 && r.median_edge_m > 0.0)
    max_edge = options.max_edge_factor * r.median_edge_m;
  if (options.max_edge_m > 0.0) max_edge = std::min(max_edge, options.max_edge_m);
  const std::size_t before_long = triangles.size();
  triangles.erase(std::remove_if(triangles.begin(), triangles.end(),
                                 [&](const Triangle& t) { return longestEdge(t) > max_edge; }),
                  triangles.end());
  r.long_edge_triangles = static_cast<long long>(before_long - triangles.size());

  // 3. A manifold soup, orientation kept.
  const std::vector<std::size_t> origin = makeManifold(triangles, n_vertices, r);
  std::vector<Point> points;
  points.reserve(origin.size());
  for (const std::size_t o : origin)
    points.emplace_back(positions[o].x(), positions[o].y(), positions[o].z());

  // The CGAL mesh: vertex i is soup point i (as polygon_soup_to_polygon_mesh
  // does), faces in the soup's orientation. Every face goes in on a manifold
  // soup; one that does not is counted with the inconsistent ones.
  Mesh mesh;
  mesh.reserve(points.size(), 3 * triangles.size() / 2 + 3, triangles.size());
  for (const Point& p : points) mesh.add_vertex(p);
  for (const Triangle& t : triangles) {
    const std::array<VertexIndex, 3> face = {VertexIndex(Mesh::size_type(t[0])),
                                             VertexIndex(Mesh::size_type(t[1])),
                                             VertexIndex(Mesh::size_type(t[2]))};
    if (CGAL::Euler::add_face(face, mesh) == Mesh::null_face()) ++r.inconsistent_triangles;
  }

  // 4. Small components.
  if (options.min_component_fraction > 0.0 && mesh.number_of_faces() > 0) {
    auto face_component = mesh.add_property_map<FaceIndex, std::size_t>("f:component", 0).first;
    const std::size_t n_components = PMP::connected_components(mesh, face_component);
    std::vector<long long> size(n_components, 0);
    for (const FaceIndex f : mesh.faces()) ++size[face_component[f]];
    const long long largest = *std::max_element(size.begin(), size.end());
    const double threshold = options.min_component_fraction * double(largest);
    std::vector<std::size_t> small;
    for (std::size_t c = 0; c < n_components; ++c)
      if (double(size[c]) < threshold) {
        small.push_back(c);
        r.component_triangles += size[c];
      }
    r.components_removed = static_cast<long long>(small.size());
    if (!small.empty()) PMP::remove_connected_components(mesh, small, face_component);
    mesh.remove_property_map(face_component);
  }
  PMP::remove_isolated_vertices(mesh);

  // Light smoothing, border fixed.
  if (options.smoothing_iterations > 0 && mesh.number_of_faces() > 0) {
    auto fixed = mesh.add_property_map<VertexIndex, bool>("v:fixed", false).first;
    for (const auto h : mesh.halfedges())
      if (mesh.is_border(h)) fixed[mesh.target(h)] = true;
    std::vector<Point> before(mesh.number_of_vertices() + mesh.number_of_removed_vertices());
    for (const VertexIndex v : mesh.vertices()) before[v.idx()] = mesh.point(v);
    // The system (mass - t L) is dominated by its diagonal for t ~ h^2, so a
    // diagonal preconditioner converges in a few iterations (CGAL's default
    // incomplete LU costs more to build than the whole solve).
    using Matrix = CGAL::Eigen_sparse_matrix<double>::EigenType;
    using Solver = CGAL::Eigen_solver_traits<Eigen::BiCGSTAB<Matrix, JacobiPreconditioner>>;
    Solver solver;
    solver.solver().setTolerance(1e-10);
    const double time = options.smoothing_step * r.median_edge_m * r.median_edge_m;
    PMP::smooth_shape(mesh, time,
                      CGAL::parameters::number_of_iterations(unsigned(options.smoothing_iterations))
                          .vertex_is_constrained_map(fixed)
                          .sparse_linear_solver(solver));
    // The solver is iterative: a fixed vertex comes back within its
    // tolerance, not bit for bit; it is put back exactly. A vertex moved
    // by half an edge or more is not noise being removed but the flow going
    // wrong (cotangent weights of a degenerate triangle): it is put back too.
    const double max_move = 0.5 * r.median_edge_m;
    for (const VertexIndex v : mesh.vertices()) {
      const Point& p = mesh.point(v);
      if (fixed[v]) {
        mesh.point(v) = before[v.idx()];
      } else if (!(CGAL::squared_distance(p, before[v.idx()]) < max_move * max_move)) {
        mesh.point(v) = before[v.idx()];
        ++r.smoothing_rejected;
      }
    }
    mesh.remove_property_map(fixed);
    // Smoothing must not turn a triangle over (a sliver whose apex moves
    // across its base): the vertices of such a triangle are put back, until
    // none is turned (a triangle with all vertices back is as it was).
    auto normal = [&](FaceIndex f, bool original) {
      const auto h = mesh.halfedge(f);
      const VertexIndex a = mesh.source(h), b = mesh.target(h), c = mesh.target(mesh.next(h));
      auto at = [&](VertexIndex v) { return toEigen(original ? before[v.idx()] : mesh.point(v)); };
      return Eigen::Vector3d((at(b) - at(a)).cross(at(c) - at(a)));
    };
    std::vector<FaceIndex> faces(mesh.faces().begin(), mesh.faces().end());
    for (bool restored = true; restored;) {
      restored = false;
      for (const FaceIndex f : faces) {
        if (normal(f, false).dot(normal(f, true)) > 0.0) continue;
        for (const VertexIndex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
          if (mesh.point(v) == before[v.idx()]) continue;
          mesh.point(v) = before[v.idx()];
          ++r.smoothing_rejected;
          restored = true;
        }
      }
    }
  }

  // Back to a SurfaceMesh, vertices in the input's order.
  std::vector<VertexIndex> kept;
  kept.reserve(mesh.number_of_vertices());
  for (const VertexIndex v : mesh.vertices()) kept.push_back(v);
  std::stable_sort(kept.begin(), kept.end(),
                   [&](VertexIndex a, VertexIndex b) { return origin[a.idx()] < origin[b.idx()]; });
  std::vector<int> dense(points.size(), -1);
  std::vector<char> input_kept(n_vertices, 0);
  SurfaceMesh out;
  out.vertices.reserve(kept.size());
  out.point_index.reserve(kept.size());
  for (const VertexIndex v : kept) {
    dense[v.idx()] = static_cast<int>(out.vertices.size());
    out.vertices.push_back(toEigen(mesh.point(v)));
    const std::size_t o = origin[v.idx()];
    out.point_index.push_back(o < input.point_index.size() ? input.point_index[o]
                                                           : static_cast<int>(o));
    input_kept[o] = 1;
  }
  out.triangles.reserve(mesh.number_of_faces());
  for (const FaceIndex f : mesh.faces()) {
    Eigen::Vector3i t;
    int k = 0;
    for (const VertexIndex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      t[k++] = dense[v.idx()];
    out.triangles.push_back(t);
  }
  r.vertices_removed = static_cast<long long>(n_vertices) -
                       std::count(input_kept.begin(), input_kept.end(), char(1));
  r.output_triangles = static_cast<long long>(out.triangles.size());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (report) *report = r;
  return out;
}

}  // namespace hsmap
