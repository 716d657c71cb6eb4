#pragma once
// WToUtmLattice: the W -> UTM map (UtmProjection::nedToUtm) over a survey's
// footprint, evaluated exactly at the nodes of a square lattice in W's
// (north, east) and interpolated bilinearly in between, for the millions of
// ray hits of the products stage (GeographicLib's exact projection costs
// ~1-2 us a point; a lattice lookup a few ns).
//
// Accuracy: the map is a rotation by the meridian convergence and a scale
// (the point scale) that both vary slowly across a survey; its second
// derivatives are of order 1/R (R the Earth's radius, ~1.6e-7 per metre), so
// bilinear interpolation over cells of h metres errs by ~h^2 / (8 R):
// 2e-8 m for 1 m cells, 8e-6 m for 20 m cells. The node spacing is
// max(min_spacing_m, extent / max_nodes_per_side), so a 10 km transect still
// needs only ~256^2 nodes.
//
// Down: W's down axis is the ORIGIN's vertical, which leans from the local
// vertical by |p| / R at a distance |p|, so a point's map position moves by
// ~|p| dz / R with its down coordinate (23 um for dz = 0.5 m at 300 m). The
// lattice therefore also holds, per node, the change of (easting, northing)
// per metre of down at `down_m` (exact difference over 1 m) and adds
// (down - down_m) times its bilinear interpolation: the residual is second
// order in dz (~|p| dz^2 / R^2, nanometres).
//
// Points outside the lattice are projected exactly (slow, but correct).
// Holds a reference to `projection`, which must outlive the lattice.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "core/geometry/utm_projection.h"

namespace hsmap {

class WToUtmLattice {
 public:
  // Covers `bounds_NE` (W north, east) with a margin of one node. Throws
  // std::invalid_argument for an empty or non-finite box.
  WToUtmLattice(const UtmProjection& projection, const Eigen::AlignedBox2d& bounds_NE,
                double down_m, double min_spacing_m = 1.0, int max_nodes_per_side = 256);

  // (easting, northing) of p_W.
  Eigen::Vector2d toUtm(const Eigen::Vector3d& p_W) const;

  double spacing() const { return spacing_; }
  const UtmProjection& projection() const { return projection_; }

 private:
  const UtmProjection& projection_;
  double down_m_;
  double north0_ = 0.0, east0_ = 0.0, spacing_ = 1.0;
  int n_rows_ = 0, n_cols_ = 0;               // nodes along north, along east
  std::vector<Eigen::Vector2d> nodes_;        // [i * n_cols_ + j]: node (north0 + i h, east0 + j h)
  std::vector<Eigen::Vector2d> per_down_;     // d(easting, northing) / d down at the node
};

}  // namespace hsmap
