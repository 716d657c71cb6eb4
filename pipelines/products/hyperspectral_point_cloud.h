#pragma once
// The hyperspectral point cloud of a run (docs/PRODUCTS.md, "Hyperspectral
// point cloud"): RUN/hyperspectral/points.ply, every UHI pixel that hit the
// surface binned into cubes of `cell_m` (2 cm by default) in W, one point a
// cell: the mean position and the mean spectrum of its hits, and their
// number (file layout: hyperspectral_point_cloud_ply.h). It is the 3-D
// product a script reads, where the ortho-image flattens the relief: on
// rugged ground a cell holds only the hits on its own piece of surface.
//
// Method
//   1. Footprint cast: every scan line of `line_poses`, in cube order, is
//      cast onto the mesh (ScanLineCaster, as the ortho-image) and only the
//      (x, y) box of its hits is kept: they give each column of cells the
//      last line that can reach it (CellReleaseMap).
//   2. Binning: the lines are cast again batch by batch, their spectra
//      streamed from the cube (EnviReader, in cube order; the cube is never
//      loaded whole; reading overlaps casting, and binning a batch overlaps
//      reading and casting the next). A hit whose spectrum has a NaN or
//      infinite band, or the cube header's `data ignore value`, is skipped
//      and counted, never binned; rays that miss are counted. After each
//      line, the cells no later line can reach are written
//      (SpectralCellBinner), so a cell is one point, never split or
//      duplicated, and memory holds only the ground the survey has not yet
//      left (bounded by max_pending_mb even when it comes back over it).
//   3. The file is written as it goes, under a temporary name, and moved
//      into place when complete.
//
// Cost: two more casts of every line (footprint and binning) and one more
// read of the cube than the ortho-image alone: 1-3 s on `rugged` (1441
// lines), 9 s on `transect-100m` (7485 lines; docs/PRODUCTS.md). The
// output is (28 + 4 * bands) bytes a point (872 B at 211 bands), ~2.2 MB
// per square metre of flat seabed at 2 cm, more on relief (rugged: 179,000
// points, 149 MiB).

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/geodetic_point.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/io/envi_reader.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "pipelines/products/scan_line_caster.h"

namespace hsmap {

struct HyperspectralPointCloudOptions {
  static constexpr double kMinCellM = 0.001, kMaxCellM = 10.0;
  // Side of the cubes the hits are binned into, metres, in [kMinCellM,
  // kMaxCellM]. 2 cm holds ~10-40 hits of a 1920-pixel UHI at 2 m; smaller
  // cells keep more detail and make a larger file (by the square).
  double cell_m = 0.02;
  // Bound of the cells waiting to be written (MB): reached only by a survey
  // that comes back over ground it has seen, whose cells are then written
  // early (and may give a second point in the same cell, counted).
  double max_pending_mb = 256.0;
  // Scan lines cast and read per batch (two batches in flight, two float
  // copies of each line: 16 lines of 1920 x 211 are ~100 MB in all).
  int lines_per_batch = 16;
  ScanLineCastOptions cast;

  // std::invalid_argument naming the field and what is allowed.
  void validate() const;
};

struct HyperspectralPointCloudReport {
  std::filesystem::path ply;
  double cell_m = 0.0;
  int bands = 0;
  std::int64_t lines = 0;
  std::int64_t lines_with_hits = 0;
  std::int64_t hits = 0;
  std::int64_t misses = 0;
  std::int64_t pixels_without_ray = 0;
  std::int64_t skipped_non_finite = 0;    // hits whose spectrum had a NaN/inf band
  std::int64_t skipped_ignore_value = 0;  // hits whose spectrum had the data ignore value
  std::int64_t binned = 0;                // hits averaged into points
  std::int64_t points = 0;
  std::int64_t early_released = 0;        // cells written before their last possible hit
  std::int64_t peak_pending_cells = 0;
  double peak_pending_mb = 0.0;
  std::int64_t bytes = 0;                 // of points.ply
  std::vector<std::pair<std::string, double>> seconds;  // per step, in order

  // A few lines for people: counts, cells, file, time.
  std::string summary() const;
};

// Writes the point cloud to `ply_path` (its folder created) from an open
// cube, its wavelengths (nm, one per band), the UHI camera, the scan line
// poses (LinePose::line = cube line), a mesh caster and W's origin (for the
// header). std::invalid_argument for bad options, a line outside the cube or
// wavelengths not matching its bands; InputError for an unreadable `data
// ignore value`; std::runtime_error when writing fails.
HyperspectralPointCloudReport writeHyperspectralPointCloud(const EnviReader& cube,
                                                           const std::vector<double>& wavelengths_nm,
                                                           const PushbroomCamera& camera,
                                                           const std::vector<LinePose>& line_poses,
                                                           const MeshRayCaster& mesh, const GeodeticPoint& origin,
                                                           const std::filesystem::path& ply_path,
                                                           const HyperspectralPointCloudOptions& options,
                                                           std::ostream& log);

}  // namespace hsmap
