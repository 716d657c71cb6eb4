#pragma once
// Synthetic scenes with known matter and free space for the surface tests:
// solids made of axis-aligned boxes (a box; a wall with an overhanging
// slab) and a height field (a plane with a bump), sampled at random points
// on their surface, each point kept with the cameras that see it (in front
// of its surface, line of sight not blocked), and small mesh measures.

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "pipelines/surface/surface_mesh.h"
#include "pipelines/surface/visibility_points.h"

namespace hsmap::surface_test {

struct Box {
  Eigen::Vector3d lo, hi;
  bool containsStrictly(const Eigen::Vector3d& x, double margin) const {
    return (x.array() > lo.array() + margin).all() && (x.array() < hi.array() - margin).all();
  }
  double distanceToSurface(const Eigen::Vector3d& x) const {
    if (containsStrictly(x, 0.0)) {
      return std::min((x - lo).minCoeff(), (hi - x).minCoeff());
    }
    return (x.cwiseMax(lo).cwiseMin(hi) - x).norm();
  }
};

// Whether the segment a -> b passes through the interior of the box shrunk
// by `margin` (slab test).
inline bool segmentHitsBox(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Box& box,
                           double margin) {
  double t0 = 0.0, t1 = 1.0;
  const Eigen::Vector3d d = b - a;
  for (int k = 0; k < 3; ++k) {
    const double lo = box.lo[k] + margin, hi = box.hi[k] - margin;
    if (std::abs(d[k]) < 1e-15) {
      if (a[k] <= lo || a[k] >= hi) return false;
      continue;
    }
    double ta = (lo - a[k]) / d[k], tb = (hi - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 >= t1) return false;
  }
  return true;
}

// A union of boxes, sampled on the part of each box's faces that is not
// inside another box, about `density` points per square metre. A point is
// seen by a camera in front of its face whose line of sight enters no box.
inline VisibilityPoints sampleBoxes(const std::vector<Box>& boxes,
                                    const std::vector<Eigen::Vector3d>& cameras, double density,
                                    unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  VisibilityPoints points;
  points.c_W = cameras;
  for (const Box& box : boxes) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = 0; side < 2; ++side) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const Eigen::Vector3d size = box.hi - box.lo;
        const int n = static_cast<int>(std::lround(density * size[u] * size[v]));
        Eigen::Vector3d normal = Eigen::Vector3d::Zero();
        normal[axis] = side ? 1.0 : -1.0;
        for (int s = 0; s < n; ++s) {
          Eigen::Vector3d p;
          p[axis] = side ? box.hi[axis] : box.lo[axis];
          p[u] = box.lo[u] + unit(rng) * size[u];
          p[v] = box.lo[v] + unit(rng) * size[v];
          bool covered = false;
          for (const Box& other : boxes)
            if (&other != &box && (other.containsStrictly(p, -1e-9) ||
                                   other.containsStrictly(p + 1e-6 * normal, 0.0)))
              covered = true;
          if (covered) continue;
          std::vector<int> seen_by;
          for (std::size_t k = 0; k < cameras.size(); ++k) {
            if ((cameras[k] - p).dot(normal) <= 0.05 * (cameras[k] - p).norm()) continue;
            const Eigen::Vector3d start = p + 1e-6 * (cameras[k] - p).normalized();
            bool blocked = false;
            for (const Box& other : boxes) blocked = blocked || segmentHitsBox(start, cameras[k], other, 1e-9);
            if (!blocked) seen_by.push_back(static_cast<int>(k));
          }
          if (seen_by.empty()) continue;
          points.p_W.push_back(p);
          points.views.push_back(std::move(seen_by));
        }
      }
    }
  }
  return points;
}

// Cameras on a sphere of `radius` about `centre` (Fibonacci lattice).
inline std::vector<Eigen::Vector3d> camerasAround(const Eigen::Vector3d& centre, double radius,
                                                  int count) {
  std::vector<Eigen::Vector3d> cameras;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / count;
    const double r = std::sqrt(1.0 - z * z);
    cameras.push_back(centre + radius * Eigen::Vector3d(r * std::cos(golden * i),
                                                        r * std::sin(golden * i), z));
  }
  return cameras;
}

// The height field z = h(x, y) over [-half, half]^2, `count` random points
// with Gaussian noise `noise` on z, seen by the cameras above it whose line
// of sight stays above the field and is within 60 degrees of the vertical.
inline VisibilityPoints sampleHeightField(const std::function<double(double, double)>& h,
                                          double half, int count, double noise,
                                          const std::vector<Eigen::Vector3d>& cameras,
                                          unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-half, half);
  std::normal_distribution<double> jitter(0.0, 1.0);
  VisibilityPoints points;
  points.c_W = cameras;
  for (int s = 0; s < count; ++s) {
    const double x = coordinate(rng), y = coordinate(rng);
    const Eigen::Vector3d p(x, y, h(x, y) + noise * jitter(rng));
    std::vector<int> seen_by;
    for (std::size_t k = 0; k < cameras.size(); ++k) {
      const Eigen::Vector3d ray = cameras[k] - p;
      if (ray.z() < 0.5 * ray.norm()) continue;
      bool blocked = false;
      for (int i = 1; i < 40 && !blocked; ++i) {
        const Eigen::Vector3d q = p + ray * (i / 40.0);
        blocked = q.z() < h(q.x(), q.y()) - 1e-3;
      }
      if (!blocked) seen_by.push_back(static_cast<int>(k));
    }
    if (seen_by.empty()) continue;
    points.p_W.push_back(p);
    points.views.push_back(std::move(seen_by));
  }
  return points;
}

inline Eigen::Vector3d triangleNormal(const SurfaceMesh& mesh, int t) {
  const Eigen::Vector3i& f = mesh.triangles[t];
  return (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
}

inline Eigen::Vector3d triangleCentroid(const SurfaceMesh& mesh, int t) {
  const Eigen::Vector3i& f = mesh.triangles[t];
  return (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3.0;
}

inline double area(const SurfaceMesh& mesh) {
  double sum = 0.0;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) sum += 0.5 * triangleNormal(mesh, t).norm();
  return sum;
}

// The signed volume enclosed (divergence theorem): positive for a closed
// mesh oriented outward.
inline double signedVolume(const SurfaceMesh& mesh) {
  double sum = 0.0;
  for (const Eigen::Vector3i& f : mesh.triangles)
    sum += mesh.vertices[f[0]].dot(mesh.vertices[f[1]].cross(mesh.vertices[f[2]])) / 6.0;
  return sum;
}

// Undirected edges used by other than exactly two triangles.
inline int openEdges(const SurfaceMesh& mesh) {
  std::map<std::pair<int, int>, int> uses;
  for (const Eigen::Vector3i& f : mesh.triangles)
    for (int j = 0; j < 3; ++j) {
      const int a = f[j], b = f[(j + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  int open = 0;
  for (const auto& [edge, count] : uses) open += count != 2;
  return open;
}

// How many triangles the vertical line through (x, y) crosses.
inline int sheetsAbove(const SurfaceMesh& mesh, double x, double y) {
  int crossings = 0;
  for (const Eigen::Vector3i& f : mesh.triangles) {
    const Eigen::Vector2d a = mesh.vertices[f[0]].head<2>(), b = mesh.vertices[f[1]].head<2>(),
                          c = mesh.vertices[f[2]].head<2>(), q(x, y);
    auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
    const double d1 = cross(b - a, q - a), d2 = cross(c - b, q - b), d3 = cross(a - c, q - c);
    if ((d1 > 0 && d2 > 0 && d3 > 0) || (d1 < 0 && d2 < 0 && d3 < 0)) ++crossings;
  }
  return crossings;
}

// Triangles per connected component (sharing a vertex), largest first.
inline std::vector<int> componentSizes(const SurfaceMesh& mesh) {
  std::vector<int> parent(mesh.vertices.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  std::function<int(int)> find = [&](int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); };
  for (const Eigen::Vector3i& f : mesh.triangles) {
    parent[find(f[1])] = find(f[0]);
    parent[find(f[2])] = find(f[0]);
  }
  std::map<int, int> sizes;
  for (const Eigen::Vector3i& f : mesh.triangles) ++sizes[find(f[0])];
  std::vector<int> out;
  for (const auto& [root, size] : sizes) out.push_back(size);
  std::sort(out.rbegin(), out.rend());
  return out;
}

}  // namespace hsmap::surface_test
