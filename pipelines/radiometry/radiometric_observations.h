#pragma once
// The evidence of the radiometry stage (docs/RADIOMETRY.md): seabed points
// seen by the UHI, each by several scan line pixels, with the geometry of
// every lamp's light path and the DN per band.
//
// A seabed point is a cell of `cell_m` × `cell_m` in W's north-east plane
// (its reflectance is taken as one spectrum per cell: what varies inside the
// cell is noise to the estimate, handled by the robust loss). A sample of the
// scan lines (at most `max_lines`, evenly spread over the survey, so that
// overlapping lanes and the altitude's changes are in it) is cast onto the
// mesh with the products' ScanLineCaster; every `sample_stride`-th pixel
// with a hit gives one observation: the UHI range r_u, per lamp that lights
// the point (not behind it, not in its shadow through the mesh) r_l, cos i_l
// and θ_l, and the pixel's DN in every band. The cube is read line by line
// (never whole).
//
// Cells seen by fewer than `min_per_cell` pixels are dropped (their
// reflectance would absorb everything they say); cells seen by more than
// `max_per_cell` keep that many, evenly spread in line order (so a cell
// crossed by two lanes keeps both); at most `max_points` cells are kept,
// evenly spread over the survey, to bound the solve.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3.h"
#include "core/io/envi_reader.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/lights_config.h"
#include "core/survey/pose_tables.h"
#include "factors/lamp_radiance_factor.h"
#include "pipelines/products/scan_line_caster.h"

namespace hsmap {

struct ObservationOptions {
  // Side of a seabed point's cell, metres (> 0). Measured (docs/RADIOMETRY.md):
  // 0.1 m against 0.2 m gave c to 0.124 instead of 0.143 /m and a reflectance
  // 34.5° instead of 45.4° from the truth on rugged-uhi-off; on tiny c 0.22
  // instead of 0.57 /m but 33.6° instead of 28.1°.
  double cell_m = 0.1;
  int max_lines = 600;      // scan lines cast (evenly spread); > 0
  int sample_stride = 0;    // every n-th pixel of a line; 0: samples / 48
  int min_per_cell = 6;     // >= 2
  int max_per_cell = 16;    // >= min_per_cell
  int max_points = 400;     // > 0
  ScanLineCastOptions cast;

  // std::invalid_argument naming the field.
  void validate() const;
};

struct RadiometricObservation {
  std::int64_t line = 0;
  int sample = 0;
  int point = 0;                // index of the seabed point (cell)
  double uhi_range_m = 0.0;     // r_u
  std::vector<LampPath> lamps;  // the lamps that light the point
  std::vector<float> dn;        // one per band
};

struct RadiometricObservations {
  int bands = 0;
  int points = 0;
  std::vector<RadiometricObservation> items;  // grouped by point, in line order within one
  // What the gathering saw.
  std::int64_t lines_cast = 0;
  std::int64_t pixels_hit = 0;
  std::int64_t pixels_unlit = 0;        // every lamp behind or shadowed
  std::int64_t pixels_not_finite = 0;   // a DN NaN or infinite
  std::int64_t lamp_paths_shadowed = 0;
  std::int64_t cells_seen = 0;          // before min_per_cell and max_points
  // The spread of the geometry over the kept observations (min, max).
  double uhi_range_min_m = 0.0, uhi_range_max_m = 0.0;
  double off_axis_max_rad = 0.0;

  std::string summary() const;
};

// Throws std::invalid_argument for bad options or a line index outside the
// cube.
RadiometricObservations gatherObservations(const EnviReader& cube, const PushbroomCamera& camera,
                                           const std::vector<LinePose>& line_poses, const MeshRayCaster& mesh,
                                           const LightsConfig& lights, const SE3d& T_C_U,
                                           const ObservationOptions& options);

}  // namespace hsmap
