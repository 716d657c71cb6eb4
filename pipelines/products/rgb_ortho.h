#pragma once
// The RGB ortho-image of a run: the textured mesh (RUN/map/mesh.ply, vertex
// colours from the RGB frames) seen from straight above on the hyperspectral
// ortho-image's grid (DATASET.md, "Results folder"):
//
//   RUN/map/rgb_ortho.png   RGBA 8-bit, one pixel per grid pixel; alpha 0 where no mesh
//   RUN/map/rgb_ortho.tif   GeoTIFF, 3 byte bands (red, green, blue) with an internal
//                           per-dataset mask (0 where no mesh), the CRS (EPSG:326zz/327zz)
//                           and geotransform of RUN/hyperspectral/ortho.tif; tiled,
//                           compressed, with overviews
//
// It sits beside the hyperspectral ortho-image for comparison, and is what the
// extrinsic refinement matches features against: every pixel therefore also
// gives the 3D point p_W it shows (RgbOrthoRenderer::render).
//
// Method. For each pixel, the vertical through its centre (the ellipsoid
// normal through the pixel centre's latitude and longitude, i.e. the points
// of W whose UTM position IS the pixel centre; UtmProjection::utmToNed) is cast
// downwards from above the mesh's bounding box (MeshRayCaster, Embree ray
// streams, one image row a batch, TBB over rows). The first hit is the
// topmost surface, as an observer above sees it (overhangs hide what is
// under them). Its colour is the barycentric interpolation of the hit
// triangle's vertex colours (RayHit::u, v), rounded to bytes; its point is
// ray origin + distance * direction. A pixel whose vertical misses the mesh
// is empty.
//
// The vertical is W's down axis leaning by |p| / R (R the Earth's radius) at
// a distance |p| from the origin; casting along W's +z instead would move the
// hit by |p| dz / R for relief dz (3 mm for 2 m of relief 10 km away, most of
// a 5 mm pixel), so the lean is kept. It costs nothing: the exact vertical
// (a point at the top of the box and the unit direction) is computed with
// GeographicLib at the nodes of a lattice of pixel positions (spacing
// max(1 m, grid extent / 254)) and interpolated bilinearly in between; both
// vary on the scale of R, so the interpolation errs by ~h^2 / (8 R): 2e-8 m
// for h = 1 m, 3e-5 m for a 10 km transect's 40 m cells.
//
// Memory. Rendering goes by bands of whole rows (RgbOrthoOptions::band_pixels):
// the writer holds one band's colours, and the GeoTIFF's tiles are written
// as each band completes (points are not kept: only render() returns them).
// Beyond that:
//   - the PNG (OpenCV's encoder takes a whole image) is a full-size buffer of
//     4 bytes a pixel: 48 MB for a 100 m transect at 5 mm (20000 x 600
//     pixels); turn write_png off for surveys much longer than that;
//   - GDAL's block cache (writing, and reading the image back for the
//     overviews) grows up to GDAL_CACHEMAX (GDAL's default: 5 % of the RAM);
//   - the renderer holds the mesh twice (its colours and the caster's copy of
//     the geometry) and MeshRayCaster's BVH.
// Measured (2 shared cores, benchmarks/rgb_ortho_tool): a 250 k-vertex mesh
// on 3.1 Mpixel (5 mm) renders in ~1 s (plus ~1 s for the BVH) and writes
// both files in ~2 s, at a peak of ~190 MB for the whole process (mesh read
// included).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "core/geometry/utm_projection.h"
#include "core/io/ply_io.h"
#include "core/raycast/mesh_ray_caster.h"
#include "pipelines/products/ortho_grid.h"

namespace hsmap {

struct RgbOrthoOptions {
  // The rays start this far (metres) above the mesh's highest point and end
  // this far below its lowest (> 0: a surface exactly at the box's top must
  // not sit on the ray's t_near, where Embree's float test may miss it).
  double margin_m = 1.0;
  // Pixels rendered at once: max(1, band_pixels / cols) whole rows, rounded
  // up to whole rows of GeoTIFF tiles when writing the GeoTIFF. The band's
  // colours (4 bytes a pixel) are held, and GDAL's copy until its tiles are
  // written; rays and hits are held one image row per thread.
  std::int64_t band_pixels = std::int64_t(1) << 20;
  bool write_png = true;
  bool write_geotiff = true;
  // GeoTIFF tiles (pixels, a multiple of 16 in [16, 4096]), lossless codec
  // (DEFLATE, ZSTD, LZW, LZMA or NONE; with horizontal-differencing
  // predictor) and overviews (AVERAGE, halving until the image fits one tile).
  int geotiff_block_size = 256;
  std::string geotiff_compression = "DEFLATE";
  bool geotiff_overviews = true;

  // std::invalid_argument naming the field and what is allowed.
  void validate() const;
};

// A window of the grid rendered: colours and the points they show.
struct RgbOrthoPatch {
  int col0 = 0;  // grid column and row of the patch's pixel (0, 0)
  int row0 = 0;
  // rows x cols, CV_8UC4 in OpenCV's channel order B, G, R, A: A = 255 where
  // the mesh was hit, 0 (with B = G = R = 0) where the pixel is empty.
  cv::Mat bgra;
  // p_W of the hit, row-major (p_W[r * cols + c]); NaN where empty.
  std::vector<Eigen::Vector3d> p_W;

  int rows() const { return bgra.rows; }
  int cols() const { return bgra.cols; }
  // (col, row) within the patch.
  bool hit(int col, int row) const { return bgra.at<cv::Vec4b>(row, col)[3] != 0; }
  const Eigen::Vector3d& point(int col, int row) const { return p_W[std::size_t(row) * cols() + col]; }
  // Red, green, blue of (col, row) within the patch.
  Eigen::Matrix<std::uint8_t, 3, 1> rgb(int col, int row) const {
    const cv::Vec4b& p = bgra.at<cv::Vec4b>(row, col);
    return {p[2], p[1], p[0]};
  }
};

class RgbOrthoRenderer {
 public:
  // The mesh must have triangles and one colour per vertex; the projection is
  // the survey origin's and must be in the grid's zone and hemisphere. Throws
  // std::invalid_argument otherwise (and for a grid of no pixels, or a
  // non-positive margin), MeshRayCaster's errors for a bad mesh. Builds the
  // BVH (TBB). Keeps a reference to nothing passed in.
  RgbOrthoRenderer(const PlyMesh& mesh, const OrthoGrid& grid, const UtmProjection& projection,
                   double margin_m = RgbOrthoOptions{}.margin_m);
  // The same, casting through `caster`, already built from the mesh's
  // vertices and triangles (std::invalid_argument when its sizes differ),
  // which must outlive the renderer: the products stage's BVH serves both
  // ortho-images (a second one took 0.5 s and ~150 MB on transect-100m).
  RgbOrthoRenderer(const PlyMesh& mesh, const MeshRayCaster& caster, const OrthoGrid& grid,
                   const UtmProjection& projection, double margin_m = RgbOrthoOptions{}.margin_m);
  ~RgbOrthoRenderer();
  RgbOrthoRenderer(const RgbOrthoRenderer&) = delete;
  RgbOrthoRenderer& operator=(const RgbOrthoRenderer&) = delete;

  const OrthoGrid& grid() const { return grid_; }

  // The window of `cols` x `rows` pixels whose upper-left pixel is grid
  // pixel (col0, row0); it must lie inside the grid and not be empty
  // (std::invalid_argument otherwise). Parallel over rows (TBB); the result
  // is the same whatever the window and the thread count (MeshRayCaster's
  // "Ties"). Thread-safe (const).
  RgbOrthoPatch render(int col0, int row0, int cols, int rows) const;
  // The same into `patch`, reusing its buffers (for many windows).
  void render(int col0, int row0, int cols, int rows, RgbOrthoPatch& patch) const;
  // Colours only, into `bgra` (as RgbOrthoPatch::bgra; reallocated unless it
  // is already rows x cols CV_8UC4, so a view into a larger image works).
  void renderColours(int col0, int row0, int cols, int rows, cv::Mat& bgra) const;

  // The ray cast for grid pixel (col, row) (continuous coordinates allowed):
  // from `margin_m` above the mesh's box, down the vertical through the
  // pixel position, to `margin_m` below the box.
  Ray verticalRay(double col, double row) const;

 private:
  struct Verticals;
  // The constructors' checks of the mesh, grid, projection and margin, and the verticals.
  void setUp(const PlyMesh& mesh, const UtmProjection& projection, double margin_m);
  void checkWindow(int col0, int row0, int cols, int rows) const;
  // Rows of `bgra` from grid pixel (col0, row0); points too unless p_W is null.
  void renderInto(int col0, int row0, cv::Mat& bgra, Eigen::Vector3d* p_W) const;

  OrthoGrid grid_;
  std::vector<Eigen::Matrix<std::uint8_t, 3, 1>> colors_;
  std::unique_ptr<MeshRayCaster> own_caster_;  // when built here
  const MeshRayCaster* caster_;
  std::unique_ptr<Verticals> verticals_;
};

struct RgbOrthoReport {
  OrthoGrid grid;
  std::int64_t pixels = 0;  // grid pixels (rays cast)
  std::int64_t hits = 0;    // pixels showing the mesh
  int bands = 0;            // bands of rows rendered
  int band_rows = 0;
  double setup_seconds = 0.0;   // BVH and verticals
  double render_seconds = 0.0;  // ray casting and colours
  double write_seconds = 0.0;   // GeoTIFF rows, overviews and PNG
  double peak_memory_mb = 0.0;  // of the process, at the end
  std::filesystem::path png, tif;  // empty when not written

  double coverage() const { return pixels > 0 ? double(hits) / double(pixels) : 0.0; }
  // One line for the run's log: grid, hits, time, memory.
  std::string summary() const;
};

// rgb_ortho.png and rgb_ortho.tif into `out_folder` (created when missing),
// each written under a temporary name and renamed when complete (AtomicFile).
// Throws std::invalid_argument for bad options, std::runtime_error when
// writing fails (naming the file; GDAL's message for the GeoTIFF).
RgbOrthoReport writeRgbOrtho(const RgbOrthoRenderer& renderer, const std::filesystem::path& out_folder,
                             const RgbOrthoOptions& options = {});

// The same, building the renderer (options.margin_m) from the mesh.
RgbOrthoReport writeRgbOrtho(const PlyMesh& mesh, const OrthoGrid& grid, const UtmProjection& projection,
                             const std::filesystem::path& out_folder, const RgbOrthoOptions& options = {});
// The same through a caster built from the mesh (RgbOrthoRenderer's second constructor).
RgbOrthoReport writeRgbOrtho(const PlyMesh& mesh, const MeshRayCaster& caster, const OrthoGrid& grid,
                             const UtmProjection& projection, const std::filesystem::path& out_folder,
                             const RgbOrthoOptions& options = {});

}  // namespace hsmap
