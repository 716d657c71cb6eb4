#pragma once
// The hyperspectral ortho-image of a run (DESIGN.md, the products stage;
// DATASET.md, "Results folder"):
//
//   RUN/hyperspectral/ortho.hdr/.raw        ENVI float32, north-up UTM grid (ortho_grid.h), every
//                                           UHI band with its wavelength; NaN where nothing was seen
//   RUN/hyperspectral/ortho.tif             the same as a COG (exportEnviToCog)
//   RUN/hyperspectral/ortho_rgb.png         quick-look, bands near 640/550/460 nm (ortho_quicklook.h)
//   RUN/hyperspectral/ancillary.hdr/.raw    4 bands on the same grid: scan line, sample, range (m),
//                                           incidence (deg) of the hit nearest the pixel centre
//
// Method
//   1. Footprint pass: every scan line of `line_poses` is cast onto the mesh
//      (ScanLineCaster: the UHI camera from the line pose T_W_U, Embree ray
//      streams, TBB over lines); only each line's bounding box of hits in W
//      is kept, plus the along-track spacing of consecutive lines' central
//      hits and the spacing of neighbouring samples (medians).
//   2. Grid: the W boxes mapped to UTM (WToUtmLattice) give each line's rows
//      of the grid and the grid itself (OrthoGrid::coveringUtm, corner
//      snapped to the pixel size).
//   3. Tiles: the grid is cut into bands of whole rows sized so that one
//      tile's accumulator fits `tile_memory_mb` (OrthoTileAccumulator: a
//      20 m transect at 5 mm, ~600 columns x 211 bands, is ~0.5 MB a row;
//      one accumulator is allocated once and cleared for every tile).
//      For each tile, the lines whose footprint reaches it (or its halo) are
//      cast again and their spectra streamed from the cube (EnviReader, in
//      cube order, batch by batch: the cube is never loaded whole; reading a
//      batch overlaps casting it); every pixel with a hit and a valid
//      spectrum adds it to the ortho pixel containing the hit. The tile is
//      averaged, gap-filled and its rows appended to the ENVI files, so peak
//      memory is two tiles whatever the survey's length.
//   4. ortho.tif and ortho_rgb.png from what was written.
//
// Pipelining (none of it changes a value: the output is the same bits as a
// sequential loop, whatever the threads):
//   - batch i is added to the tile (sequentially, lines in cube order) while
//     batch i + 1 is read, cast, transposed and checked (two batch buffers);
//   - tile t is written by a second thread while tile t + 1 is accumulated
//     (two accumulators, used in turn; rows still go out in order);
//   - ortho.raw and ancillary.raw are written with O_DIRECT (EnviWriter's
//     direct mode).
// Where the time goes (transect-100m, 7485 lines, 100 m at 5 mm: a grid of
// 920 x 19993 pixels, so ortho.raw is 920 * 19993 * 211 * 4 B = 15.5 GB,
// 2.7 times the cube): writing ortho.raw is the floor. Through the page
// cache the project's virtual machine wrote it at ~0.2 GB/s (75 s, and it
// evicted the cube); with O_DIRECT at up to ~1.3 GB/s. The ortho is
// ~bands * 4 / (5 mm)^2 = 34 GB per 1000 m^2 of grid: a larger pixel_m
// shrinks it by the square. Fresh memory is the other cost there (a 4 KB
// page fault ~30 us): buffers are allocated once, the accumulators' sums in
// huge pages, and a tile reset clears 5 bytes a pixel, not ~870.
//
// Values: the ortho pixel is the MEAN of the spectra whose hit fell in it
// (OrthoTileAccumulator). A pixel's spectrum is skipped (counted, never
// painted) when any band is NaN or infinite, or equals the cube header's
// `data ignore value` (counted apart). Gap filling: an empty pixel is filled
// by inverse-distance weighting of observed pixels within
// r = ceil(max(line spacing, sample spacing) / pixel) pixels (the medians,
// capped by max_fill_radius_px) that surround it (both sides along a row or
// a column), so holes between lines close and nothing is invented beyond the
// sampling's own spacing; NaN stays where nothing was seen. Where the lines
// lie farther apart than the median (the outer side of a turn, a faster
// stretch), a hit reaches as far as its line's local spacing at its sample
// (the distance to where the neighbouring lines' same pixel sees, up to
// max_fill_radius_px; not within max_fill_radius_px of the swath's sides),
// so the fanned lines of a turn leave no stripes of NaN between them.
//
// Empty pixels are NaN, and the ENVI headers say so: `data ignore value =
// NaN` (product_headers.h), which GDAL reports as NoData, like the COG's
// nodata (geotiff_export.h).
//
// Lines whose footprint reaches two tiles are cast and read once per tile
// (only the lines near tile edges for a survey along north-south; for a
// survey going east-west, where every line crosses every tile, the cube is
// read once per tile: raise tile_memory_mb).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/utm_projection.h"
#include "core/io/envi_header.h"
#include "core/io/envi_reader.h"
#include "core/io/geotiff_export.h"
#include "core/io/ply_io.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "core/survey/survey.h"
#include "pipelines/products/ortho_grid.h"
#include "pipelines/products/scan_line_caster.h"

namespace hsmap {

struct HyperspectralOptions {
  // Ortho pixel size, metres (> 0). 5 mm resolves what a 1920-pixel UHI sees
  // from 2 m; larger for a quick product.
  double pixel_m = 0.005;
  // Gap-filling radius in pixels: -1 = from the sampling (ceil of the larger
  // of the line spacing and the sample spacing over the pixel size), 0 = no
  // filling, > 0 as given.
  int fill_radius_px = -1;
  // Upper bound of the automatic radius and of a hit's local reach (a
  // stalled vehicle, a single line seen far away, a fast turn must not smear
  // spectra over centimetres).
  int max_fill_radius_px = 8;
  // Memory of one tile's accumulator (MB); the tile's rows follow from it.
  // Two accumulators are held (one accumulating while the other is written).
  double tile_memory_mb = 256.0;
  // Scan lines cast and read per batch (two batches in flight, two float
  // copies of each line: 32 lines of 1920 x 211 are ~200 MB in all).
  int lines_per_batch = 32;
  ScanLineCastOptions cast;
  EnviInterleave interleave = EnviInterleave::bil;
  bool write_geotiff = true;
  GeoTiffExportOptions geotiff;
  bool write_quicklook = true;
  int quicklook_max_side = 8192;
  // The UHI camera; default: the survey's uhi.camera (writeHyperspectralProducts).
  std::optional<PushbroomParameters> camera;
  // Called once the ortho grid is set, before the first tile: a caller can
  // start a product on the same grid (the RGB ortho-image) alongside the
  // tiles, whose pace is the disk's while the cores have time to spare.
  std::function<void(const OrthoGrid&)> on_grid;

  // std::invalid_argument naming the field and what is allowed.
  void validate() const;
};

struct HyperspectralReport {
  std::int64_t lines = 0;            // scan lines cast (line poses)
  std::int64_t lines_with_hits = 0;
  std::int64_t pixels_cast = 0;      // rays cast in the footprint pass
  std::int64_t pixels_without_ray = 0;
  std::int64_t hits = 0;
  std::int64_t misses = 0;
  std::int64_t skipped_non_finite = 0;  // hits whose spectrum had a NaN/inf band
  std::int64_t skipped_ignore_value = 0;  // hits whose spectrum had the data ignore value
  std::int64_t painted = 0;          // hits whose spectrum went into the ortho-image

  OrthoGrid grid;
  int bands = 0;
  int tiles = 0;
  int tile_rows = 0;
  double line_spacing_m = 0.0;       // median along-track spacing of central hits
  double sample_spacing_m = 0.0;     // median spacing of neighbouring central samples
  int fill_radius_px = 0;
  std::int64_t observed_pixels = 0;  // ortho pixels with at least one hit
  std::int64_t filled_pixels = 0;    // gap-filled ortho pixels
  std::int64_t lines_read = 0;       // cube lines read over all tiles (>= lines_with_hits)

  std::vector<std::pair<std::string, double>> seconds;  // per step, in order
  double peak_memory_mb = 0.0;                 // of the process, at the end
  double peak_memory_before_geotiff_mb = 0.0;  // of the process, before exportEnviToCog

  std::filesystem::path ortho_hdr, ortho_tif, quicklook_png, ancillary_hdr;

  std::int64_t validPixels() const { return observed_pixels + filled_pixels; }
  // Valid pixels / grid pixels.
  double coverage() const;
  // A few lines for people: counts, grid, coverage, time per step.
  std::string summary() const;
};

// The ortho-image and its companions into `out_folder` (created), from an
// open cube, its wavelengths (nm, one per band), the UHI camera, the scan
// line poses (LinePose::line = cube line), a mesh caster and the survey's UTM
// projection. Throws std::invalid_argument for bad options, a line index
// outside the cube or wavelengths not matching its bands; std::runtime_error
// when no ray hits the mesh or writing fails; InputError for an unreadable
// `data ignore value`.
HyperspectralReport writeHyperspectralOrtho(const EnviReader& cube,
                                            const std::vector<double>& wavelengths_nm,
                                            const PushbroomCamera& camera,
                                            const std::vector<LinePose>& line_poses,
                                            const MeshRayCaster& mesh,
                                            const UtmProjection& projection,
                                            const std::filesystem::path& out_folder,
                                            const HyperspectralOptions& options, std::ostream& log);

// The surface the lines are cast onto (RUN/map/mesh.ply): readPly's errors,
// and InputError naming the file when it has no triangles.
PlyMesh readSurfaceMesh(const std::filesystem::path& mesh_ply);

// One cast of the survey's cube with the mesh read from a file (tests and
// benchmarks; the products stage holds its mesh: product_casting.h): the
// survey's cube, wavelengths, origin
// and (unless options.camera) UHI camera; the mesh read from `mesh_ply`
// (RUN/map/mesh.ply; InputError when it has no triangles); outputs in
// `out_folder` (RUN/hyperspectral).
HyperspectralReport writeHyperspectralProducts(const Survey& survey,
                                               const std::vector<LinePose>& line_poses,
                                               const std::filesystem::path& mesh_ply,
                                               const std::filesystem::path& out_folder,
                                               const HyperspectralOptions& options,
                                               std::ostream& log);

}  // namespace hsmap
