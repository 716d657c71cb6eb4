#include "pipelines/simulate/scene/rock_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "pipelines/simulate/scene/procedural_noise.h"
#include "pipelines/simulate/scene/random_draw.h"

namespace hsmap {

namespace {

// Index of the (unit-length) midpoint of edge (a, b), created once per edge so
// neighbouring triangles share it and the mesh stays closed.
class MidpointCache {
 public:
  explicit MidpointCache(std::vector<Eigen::Vector3d>& vertices) : vertices_(vertices) {}
  int midpoint(int a, int b) {
    const std::pair<int, int> key(std::min(a, b), std::max(a, b));
    const auto found = cache_.find(key);
    if (found != cache_.end()) return found->second;
    vertices_.push_back((vertices_[a] + vertices_[b]).normalized());
    const int index = static_cast<int>(vertices_.size()) - 1;
    cache_.emplace(key, index);
    return index;
  }

 private:
  std::vector<Eigen::Vector3d>& vertices_;
  std::map<std::pair<int, int>, int> cache_;
};

}  // namespace

TriangleMesh makeIcosphere(int subdivisions) {
  if (subdivisions < 0 || subdivisions > 7) {
    throw std::invalid_argument("makeIcosphere: subdivisions must be in [0, 7], got " +
                                std::to_string(subdivisions));
  }
  // The 12 vertices of the icosahedron are the cyclic permutations of
  // (0, +-1, +-phi); its 20 faces are the triples of mutually adjacent ones
  // (pairwise distance 2, the edge length).
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh mesh;
  for (double s1 : {-1.0, 1.0}) {
    for (double s2 : {-phi, phi}) {
      mesh.vertices.emplace_back(0.0, s1, s2);
      mesh.vertices.emplace_back(s1, s2, 0.0);
      mesh.vertices.emplace_back(s2, 0.0, s1);
    }
  }
  const int n = static_cast<int>(mesh.vertices.size());
  auto adjacent = [&](int a, int b) {
    return std::abs((mesh.vertices[a] - mesh.vertices[b]).norm() - 2.0) < 1e-9;
  };
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      for (int c = b + 1; c < n; ++c) {
        if (!adjacent(a, b) || !adjacent(b, c) || !adjacent(a, c)) continue;
        const Eigen::Vector3d& pa = mesh.vertices[a];
        const Eigen::Vector3d normal = (mesh.vertices[b] - pa).cross(mesh.vertices[c] - pa);
        // Wind every face so that its normal points away from the centre.
        if (normal.dot(pa) > 0.0) {
          mesh.triangles.emplace_back(a, b, c);
        } else {
          mesh.triangles.emplace_back(a, c, b);
        }
      }
    }
  }
  for (auto& v : mesh.vertices) v.normalize();

  for (int level = 0; level < subdivisions; ++level) {
    MidpointCache cache(mesh.vertices);
    std::vector<Eigen::Vector3i> finer;
    finer.reserve(mesh.triangles.size() * 4);
    for (const Eigen::Vector3i& t : mesh.triangles) {
      const int ab = cache.midpoint(t[0], t[1]);
      const int bc = cache.midpoint(t[1], t[2]);
      const int ca = cache.midpoint(t[2], t[0]);
      // The four children keep the parent's winding.
      finer.emplace_back(t[0], ab, ca);
      finer.emplace_back(ab, t[1], bc);
      finer.emplace_back(ca, bc, t[2]);
      finer.emplace_back(ab, bc, ca);
    }
    mesh.triangles = std::move(finer);
  }
  return mesh;
}

TriangleMesh makeRockMesh(const RockShape& shape, const TriangleMesh& unit_sphere) {
  if (!(shape.semi_axes_m.minCoeff() > 0.0) || !shape.semi_axes_m.allFinite()) {
    throw std::invalid_argument("makeRockMesh: semi_axes_m must be positive and finite");
  }
  if (!(shape.roughness >= 0.0 && shape.roughness <= 0.9)) {
    std::ostringstream message;
    message << "makeRockMesh: roughness must be in [0, 0.9], got " << shape.roughness;
    throw std::invalid_argument(message.str());
  }
  if (shape.planar_cuts < 0) {
    throw std::invalid_argument("makeRockMesh: planar_cuts must be >= 0, got " +
                                std::to_string(shape.planar_cuts));
  }
  std::mt19937_64 rng(shape.seed);
  const std::uint64_t shape_seed = rng(), fine_seed = rng();
  struct Plane {
    Eigen::Vector3d normal;
    double distance;
  };
  std::vector<Plane> planes;
  for (int k = 0; k < shape.planar_cuts; ++k) {
    // A uniformly distributed direction: points of the cube kept when inside
    // the unit ball (not std::normal_distribution, which differs between
    // standard libraries).
    Eigen::Vector3d normal;
    do {
      // One draw per statement: the evaluation order of function arguments
      // is unspecified, and the scene must not depend on the compiler.
      normal.x() = uniformDraw(rng, -1, 1);
      normal.y() = uniformDraw(rng, -1, 1);
      normal.z() = uniformDraw(rng, -1, 1);
    } while (normal.squaredNorm() > 1.0 || normal.squaredNorm() < 1e-4);
    planes.push_back({normal.normalized(), uniformDraw(rng, 0.65, 0.9)});
  }

  static constexpr FbmParameters kShape{1.1, 4, 2.03, 0.5};
  TriangleMesh rock;
  rock.triangles = unit_sphere.triangles;
  rock.vertices.reserve(unit_sphere.vertices.size());
  const Eigen::Matrix3d R_W_R = shape.q_W_R.normalized().toRotationMatrix();
  for (const Eigen::Vector3d& d : unit_sphere.vertices) {
    double r = 1.0 + shape.roughness * fbm3(shape_seed, d, kShape);
    for (const Plane& plane : planes) {
      const double cosine = d.dot(plane.normal);
      if (cosine > 0.0) r = std::min(r, plane.distance / cosine);
    }
    r *= 1.0 + 0.03 * gradientNoise3(fine_seed, 9.0 * d);
    rock.vertices.push_back(R_W_R * shape.semi_axes_m.cwiseProduct(r * d));
  }
  return rock;
}

}  // namespace hsmap
