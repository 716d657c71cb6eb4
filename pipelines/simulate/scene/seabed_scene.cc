#include "pipelines/simulate/scene/seabed_scene.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "core/geometry/so3.h"
#include "pipelines/simulate/scene/random_draw.h"
#include "pipelines/simulate/scene/rock_mesh.h"
#include "pipelines/simulate/scene/seabed_height_field.h"

namespace hsmap {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Boulders are stratified: one in each cell of 1.5 m (north) x 2 m (east),
// the cells aligned so that one column is the vehicle's corridor |east| <= 1 m
// (a lawnmower's other lanes get the same density).
constexpr double kCellNorthM = 1.5;
constexpr double kCellEastM = 2.0;
constexpr double kMinCellEastM = 0.5;  // narrower edge columns get no boulders
constexpr int kPlacementTries = 30;

// Samples `field` on the grid and appends its triangles.
void appendSeabedGrid(const SeabedHeightField& field, SeabedScene& scene) {
  const SeabedSceneConfig& c = field.config();
  const double north_length = c.north_max_m - c.north_min_m;
  const double east_length = c.east_max_m - c.east_min_m;
  // The 1e-9 keeps an extent that is a multiple of cell_m from gaining a
  // sliver row through rounding (26 / 0.02 = 1300.0000000000002).
  const int rows = std::max(1, static_cast<int>(std::ceil(north_length / c.cell_m - 1e-9)));
  const int cols = std::max(1, static_cast<int>(std::ceil(east_length / c.cell_m - 1e-9)));
  const int stride = cols + 1;
  const auto coordinate = [](double lo, double hi, int i, int n) {
    return i == n ? hi : lo + (hi - lo) * static_cast<double>(i) / n;
  };

  const std::size_t first_vertex = scene.vertices.size();
  scene.vertices.resize(first_vertex + static_cast<std::size_t>(rows + 1) * stride);
  tbb::parallel_for(0, rows + 1, [&](int i) {
    const double north = coordinate(c.north_min_m, c.north_max_m, i, rows);
    Eigen::Vector3d* row = &scene.vertices[first_vertex + static_cast<std::size_t>(i) * stride];
    for (int j = 0; j <= cols; ++j) {
      const double east = coordinate(c.east_min_m, c.east_max_m, j, cols);
      row[j] = Eigen::Vector3d(north, east, field.z(north, east));
    }
  });

  const std::size_t first_triangle = scene.triangles.size();
  scene.triangles.resize(first_triangle + 2 * static_cast<std::size_t>(rows) * cols);
  scene.triangle_kind.resize(scene.triangles.size(), SurfaceKind::seabed);
  const int base = static_cast<int>(first_vertex);
  tbb::parallel_for(0, rows, [&](int i) {
    Eigen::Vector3i* out =
        &scene.triangles[first_triangle + 2 * static_cast<std::size_t>(i) * cols];
    for (int j = 0; j < cols; ++j) {
      const int v00 = base + i * stride + j;  // (north i, east j)
      const int v10 = v00 + stride;           // one step north
      const int v01 = v00 + 1;                // one step east
      const int v11 = v10 + 1;
      // east x north = -z (up): (v00, v01, v10) and (v01, v11, v10) face up.
      out[2 * j] = Eigen::Vector3i(v00, v01, v10);
      out[2 * j + 1] = Eigen::Vector3i(v01, v11, v10);
    }
  });
}

// Adds rocks to the scene, resting on the seabed.
class RockPlacer {
 public:
  RockPlacer(const SeabedHeightField& field, SeabedScene& scene, std::uint64_t seed)
      : field_(field), scene_(scene), rng_(seed) {
    spheres_[0] = makeIcosphere(3);
    spheres_[1] = makeIcosphere(4);
  }

  std::mt19937_64& rng() { return rng_; }

  struct Placed {
    double top_z;  // smallest z_W of the rock (its highest point)
  };

  // The mesh of `shape` (vertices relative to its centre), made from the
  // finer sphere for rocks 0.4 m across and more.
  TriangleMesh shapeMesh(const RockShape& shape) const {
    const int level = shape.semi_axes_m.head<2>().maxCoeff() >= 0.2 ? 1 : 0;
    return makeRockMesh(shape, spheres_[level]);
  }

  // Appends `shape` centred horizontally at (north, east), lowered until its
  // lowest point is `sink_m` below the deepest seabed point under it.
  Placed placeOnSeabed(const RockShape& shape, double north, double east, double sink_m) {
    TriangleMesh mesh = shapeMesh(shape);
    const double reach = horizontalReach(mesh);
    // Deepest seabed point under the rock (centre and a ring at 70% of its
    // reach): on a slope the rock then touches the downhill side and is
    // buried deeper uphill, as a rock that slid there would be.
    double deepest_z = field_.z(north, east);
    for (int k = 0; k < 8; ++k) {
      const double angle = 2.0 * kPi * k / 8.0;
      deepest_z = std::max(deepest_z, field_.z(north + 0.7 * reach * std::cos(angle),
                                               east + 0.7 * reach * std::sin(angle)));
    }
    return append(mesh, north, east, deepest_z + sink_m);
  }

  // Appends `mesh` centred horizontally at (north, east) with its lowest
  // point at z_W = bottom_z.
  Placed append(const TriangleMesh& mesh, double north, double east, double bottom_z) {
    double lowest = -1e300, highest = 1e300;
    for (const auto& v : mesh.vertices) {
      lowest = std::max(lowest, v.z());
      highest = std::min(highest, v.z());
    }
    const Eigen::Vector3d centre_W(north, east, bottom_z - lowest);
    const int base = static_cast<int>(scene_.vertices.size());
    for (const auto& v : mesh.vertices) scene_.vertices.push_back(centre_W + v);
    for (const auto& t : mesh.triangles) {
      scene_.triangles.push_back(t + Eigen::Vector3i::Constant(base));
      scene_.triangle_kind.push_back(SurfaceKind::rock);
    }
    footprints_.push_back({north, east, horizontalReach(mesh)});
    return {centre_W.z() + highest};
  }

  // True when a rock of horizontal reach `reach` at (north, east) would not
  // overlap any rock placed so far.
  bool isFree(double north, double east, double reach) const {
    for (const auto& f : footprints_) {
      if (std::hypot(north - f[0], east - f[1]) < 1.05 * (reach + f[2])) return false;
    }
    return true;
  }

  static double horizontalReach(const TriangleMesh& mesh) {
    double reach = 0.0;
    for (const auto& v : mesh.vertices) reach = std::max(reach, v.head<2>().norm());
    return reach;
  }

 private:
  const SeabedHeightField& field_;
  SeabedScene& scene_;
  std::mt19937_64 rng_;
  std::array<TriangleMesh, 2> spheres_;
  std::vector<std::array<double, 3>> footprints_;  // north, east, reach
};

// Random heading, roll and pitch within +-tilt_deg. Random draws are made one
// per statement throughout this file: the evaluation order of function
// arguments is unspecified, and the scene must not depend on the compiler.
Eigen::Quaterniond randomAttitude(std::mt19937_64& rng, double tilt_deg) {
  const double roll_deg = uniformDraw(rng, -tilt_deg, tilt_deg);
  const double pitch_deg = uniformDraw(rng, -tilt_deg, tilt_deg);
  const double heading_deg = uniformDraw(rng, -180.0, 180.0);
  return quaternionFromRollPitchHeadingDeg(roll_deg, pitch_deg, heading_deg);
}

// A boulder 0.2-0.8 m across, small ones more frequent, tilted a little.
RockShape randomBoulder(std::mt19937_64& rng) {
  RockShape shape;
  const double u = uniformDraw(rng, 0.0, 1.0);
  const double radius = 0.1 + 0.3 * std::pow(u, 1.8);
  const double width = radius * uniformDraw(rng, 0.65, 1.0);
  const double height = radius * uniformDraw(rng, 0.5, 0.85);
  shape.semi_axes_m = Eigen::Vector3d(radius, width, height);
  shape.roughness = uniformDraw(rng, 0.15, 0.35);
  shape.planar_cuts = static_cast<int>(uniformDraw(rng, 2.0, 7.0));
  shape.q_W_R = randomAttitude(rng, 12.0);
  shape.seed = rng();
  return shape;
}

// Draws boulders at random (north, east) from `draw_position` until one fits.
template <class DrawPosition>
void placeRandomBoulder(RockPlacer& placer, DrawPosition draw_position) {
  std::mt19937_64& rng = placer.rng();
  const RockShape shape = randomBoulder(rng);
  const double sink_fraction = uniformDraw(rng, 0.1, 0.3);
  // Rough reach before meshing, to keep rocks from overlapping.
  const double reach = shape.semi_axes_m.x() * (1.0 + 0.87 * shape.roughness);
  for (int attempt = 0; attempt < kPlacementTries; ++attempt) {
    const Eigen::Vector2d ne = draw_position(reach);
    if (!placer.isFree(ne.x(), ne.y(), reach)) continue;
    placer.placeOnSeabed(shape, ne.x(), ne.y(), sink_fraction * 2.0 * shape.semi_axes_m.z());
    return;
  }
}

// A boulder perched on a smaller pedestal rock: its widest part is well above
// the seabed, so its underside faces down over open water.
void placePerchedBoulder(RockPlacer& placer, double north, double east) {
  std::mt19937_64& rng = placer.rng();
  RockShape pedestal;
  pedestal.semi_axes_m = Eigen::Vector3d(0.2, 0.17, 0.22);
  pedestal.roughness = 0.2;
  pedestal.planar_cuts = 3;
  pedestal.q_W_R = quaternionFromRollPitchHeadingDeg(0.0, 0.0, uniformDraw(rng, -180.0, 180.0));
  pedestal.seed = rng();
  const RockPlacer::Placed base = placer.placeOnSeabed(pedestal, north, east, 0.06);

  RockShape top;
  top.semi_axes_m = Eigen::Vector3d(0.42, 0.34, 0.2);
  top.roughness = 0.12;
  top.planar_cuts = 3;
  top.q_W_R = randomAttitude(rng, 8.0);
  top.seed = rng();
  // Its lowest point 4 cm into the pedestal's top, so the two touch.
  placer.append(placer.shapeMesh(top), north, east, base.top_z + 0.04);
}

// A slab leaning from the seabed onto a support rock: a tilted roof whose
// underside faces down, 0-0.35 m above the seabed.
void placeLeaningSlab(RockPlacer& placer, const SeabedHeightField& field, double north,
                      double east) {
  std::mt19937_64& rng = placer.rng();
  const double heading = uniformDraw(rng, -180.0, 180.0) * kPi / 180.0;
  const Eigen::Vector2d direction(std::cos(heading), std::sin(heading));
  constexpr double kSpanM = 1.0;  // horizontal distance from the slab's foot to the support
  const Eigen::Vector2d foot = Eigen::Vector2d(north, east) - 0.5 * kSpanM * direction;
  const Eigen::Vector2d support = foot + kSpanM * direction;

  RockShape support_rock;
  support_rock.semi_axes_m = Eigen::Vector3d(0.22, 0.2, 0.2);
  support_rock.roughness = 0.15;
  support_rock.planar_cuts = 3;
  support_rock.q_W_R = quaternionFromRollPitchHeadingDeg(0.0, 0.0, uniformDraw(rng, -180.0, 180.0));
  support_rock.seed = rng();
  const RockPlacer::Placed rest =
      placer.placeOnSeabed(support_rock, support.x(), support.y(), 0.05);

  // The slab's underside runs from 3 cm below the seabed at its foot to 2 cm
  // into the top of the support rock.
  const Eigen::Vector3d foot_W(foot.x(), foot.y(), field.z(foot.x(), foot.y()) + 0.03);
  const Eigen::Vector3d rest_W(support.x(), support.y(), rest.top_z + 0.02);
  const double rise = foot_W.z() - rest_W.z();  // up is -z
  const double pitch_deg = std::atan2(rise, kSpanM) * 180.0 / kPi;

  RockShape slab;
  slab.semi_axes_m = Eigen::Vector3d(0.66, 0.4, 0.07);
  slab.roughness = 0.06;
  slab.planar_cuts = 2;
  // Positive pitch raises the slab's +x end (NED: x -> (cos, 0, -sin)), which
  // heads towards the support.
  const double roll_deg = uniformDraw(rng, -4.0, 4.0);
  slab.q_W_R = quaternionFromRollPitchHeadingDeg(roll_deg, pitch_deg, heading * 180.0 / kPi);
  slab.seed = rng();
  const TriangleMesh mesh = placer.shapeMesh(slab);
  // Centre: the middle of the underside line, raised by the half thickness
  // along the slab's own up axis (-z of R).
  const Eigen::Vector3d down_W = slab.q_W_R * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d centre_W = 0.5 * (foot_W + rest_W) - slab.semi_axes_m.z() * down_W;
  double lowest = -1e300;
  for (const auto& v : mesh.vertices) lowest = std::max(lowest, v.z());
  placer.append(mesh, centre_W.x(), centre_W.y(), centre_W.z() + lowest);
}

void appendRocks(const SeabedHeightField& field, SeabedScene& scene, std::uint64_t seed) {
  const SeabedSceneConfig& c = field.config();
  RockPlacer placer(field, scene, seed);
  std::mt19937_64& rng = placer.rng();
  const double north_length = c.north_max_m - c.north_min_m;
  // A coordinate drawn in [lo, hi], kept `reach` inside the extent [min, max]
  // when the extent is wide enough, so rocks do not hang over its edges.
  const auto inside = [&](double lo, double hi, double min, double max, double reach) {
    const double value = uniformDraw(rng, lo, hi);
    if (max - min <= 2.0 * reach) return 0.5 * (min + max);
    return std::clamp(value, min + reach, max - reach);
  };
  const auto clampEast = [&](double east) { return std::clamp(east, c.east_min_m, c.east_max_m); };

  placePerchedBoulder(placer, c.north_min_m + 0.2 * north_length,
                      clampEast(uniformDraw(rng, -0.5, 0.5)));
  placeLeaningSlab(placer, field, c.north_min_m + 0.82 * north_length,
                   clampEast(uniformDraw(rng, -0.4, 0.4)));

  const int rows = std::max(1, static_cast<int>(std::floor(north_length / kCellNorthM)));
  // Columns [-1 + 2k, 1 + 2k] m for every k that overlaps the extent.
  const int first_column =
      static_cast<int>(std::floor((c.east_min_m + 0.5 * kCellEastM) / kCellEastM));
  const int last_column =
      static_cast<int>(std::floor((c.east_max_m + 0.5 * kCellEastM) / kCellEastM));
  for (int row = 0; row < rows; ++row) {
    const double north_lo = c.north_min_m + north_length * row / rows;
    const double north_hi = c.north_min_m + north_length * (row + 1) / rows;
    for (int column = first_column; column <= last_column; ++column) {
      const double east_lo = std::max(c.east_min_m, (column - 0.5) * kCellEastM);
      const double east_hi = std::min(c.east_max_m, (column + 0.5) * kCellEastM);
      if (east_hi - east_lo < kMinCellEastM) continue;
      placeRandomBoulder(placer, [&](double reach) {
        const double north = inside(north_lo, north_hi, c.north_min_m, c.north_max_m, reach);
        const double east = inside(east_lo, east_hi, c.east_min_m, c.east_max_m, reach);
        return Eigen::Vector2d(north, east);
      });
    }
  }
}

}  // namespace

SeabedScene buildSeabedScene(const SeabedSceneConfig& config) {
  const SeabedHeightField field(config);  // validates
  SeabedScene scene;
  appendSeabedGrid(field, scene);
  if (config.terrain == TerrainPreset::rugged) {
    // A seed for the rocks that differs from the height field's draws.
    appendRocks(field, scene, config.seed ^ 0x5eabed5cee5eedULL);
  }
  // Built in the track's frame, so that the rugged features stay under the
  // track at any heading; turned into W last. A rotation about the vertical
  // keeps the triangles' winding (normals still point out). Skipped at 0 so
  // that the default scene keeps its bits.
  if (config.heading_deg != 0.0) {
    const double heading = config.heading_deg * kPi / 180.0;
    const double cos_h = std::cos(heading);
    const double sin_h = std::sin(heading);
    tbb::parallel_for(std::size_t(0), scene.vertices.size(), [&](std::size_t i) {
      Eigen::Vector3d& v = scene.vertices[i];
      const double north = v.x() - config.pivot_north_m;
      const double east = v.y() - config.pivot_east_m;
      v.x() = config.pivot_north_m + cos_h * north - sin_h * east;
      v.y() = config.pivot_east_m + sin_h * north + cos_h * east;
    });
  }
  return scene;
}

}  // namespace hsmap
