#include "pipelines/products/rgb_ortho.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>
#include <opencv2/imgcodecs.hpp>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/io/atomic_file.h"
#include "core/io/geotiff_export.h"
#include "core/util/stage_timer.h"

namespace hsmap {

namespace {

using Clock = std::chrono::steady_clock;

void require(bool ok, const std::string& field, const std::string& expected) {
  if (!ok) throw std::invalid_argument("RGB ortho options: " + field + ": expected " + expected);
}

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

// ---- GeoTIFF through GDAL ---------------------------------------------------

// While alive, GDAL's failures on this thread are collected instead of
// printed, and GDAL writes no .aux.xml side file (it would follow the
// .partial name). The GeoTIFF's mask goes inside the file.
class GdalQuiet {
 public:
  GdalQuiet() {
    CPLErrorReset();
    CPLPushErrorHandlerEx(&GdalQuiet::handle, this);
    CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO");
    CPLSetThreadLocalConfigOption("GDAL_TIFF_INTERNAL_MASK", "YES");
  }
  ~GdalQuiet() {
    CPLSetThreadLocalConfigOption("GDAL_TIFF_INTERNAL_MASK", nullptr);
    CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", nullptr);
    CPLPopErrorHandler();
  }
  GdalQuiet(const GdalQuiet&) = delete;
  GdalQuiet& operator=(const GdalQuiet&) = delete;

  bool failed() const { return !message_.empty(); }
  const std::string& message() const { return message_; }

 private:
  static void CPL_STDCALL handle(CPLErr level, CPLErrorNum, const char* message) {
    if (level != CE_Failure && level != CE_Fatal) return;
    auto* self = static_cast<GdalQuiet*>(CPLGetErrorHandlerUserData());
    if (self->message_.empty()) self->message_ = message != nullptr ? message : "unknown GDAL error";
  }
  std::string message_;
};

// The GeoTIFF of the RGB ortho-image, written band of rows by band of rows
// (GTiff driver: tiled, so GDAL's block cache holds at most a row of tiles
// of unfinished blocks).
class RgbGeoTiff {
 public:
  RgbGeoTiff(const std::filesystem::path& path, const OrthoGrid& grid, const RgbOrthoOptions& options)
      : path_(path), grid_(grid), options_(options) {
    registerGdalDrivers();
    GDALDriverH driver = GDALGetDriverByName("GTiff");
    if (driver == nullptr) fail("GDAL has no GTiff driver");
    const std::string compression = upper(options.geotiff_compression);
    char** create = nullptr;
    create = CSLSetNameValue(create, "TILED", "YES");
    create = CSLSetNameValue(create, "BLOCKXSIZE", std::to_string(options.geotiff_block_size).c_str());
    create = CSLSetNameValue(create, "BLOCKYSIZE", std::to_string(options.geotiff_block_size).c_str());
    create = CSLSetNameValue(create, "COMPRESS", compression.c_str());
    if (compression != "NONE") create = CSLSetNameValue(create, "PREDICTOR", "2");
    create = CSLSetNameValue(create, "PHOTOMETRIC", "RGB");
    create = CSLSetNameValue(create, "INTERLEAVE", "PIXEL");
    create = CSLSetNameValue(create, "BIGTIFF", "IF_SAFER");
    dataset_.handle = GDALCreate(driver, path.c_str(), grid.cols, grid.rows, 3, GDT_Byte, create);
    CSLDestroy(create);
    if (dataset_.handle == nullptr) fail("cannot create it");

    // {x0, px, 0, y0, 0, -px}: the upper-left corner of the upper-left pixel.
    double transform[6] = {grid.west_m, grid.pixel_m, 0.0, grid.north_m, 0.0, -grid.pixel_m};
    if (GDALSetGeoTransform(dataset_, transform) != CE_None) fail("cannot set the geotransform");
    setUtmCrs();
    if (GDALCreateDatasetMaskBand(dataset_, GMF_PER_DATASET) != CE_None) fail("cannot create the mask");
    mask_ = GDALGetMaskBand(GDALGetRasterBand(dataset_, 1));
    if (mask_ == nullptr) fail("no mask band");
    checkQuiet();
  }
  RgbGeoTiff(const RgbGeoTiff&) = delete;
  RgbGeoTiff& operator=(const RgbGeoTiff&) = delete;

  // Rows row0 .. row0 + bgra.rows - 1 (full width).
  void writeRows(int row0, const cv::Mat& bgra) {
    auto* data = const_cast<std::uint8_t*>(bgra.ptr<std::uint8_t>());
    const int cols = bgra.cols, rows = bgra.rows;
    const GSpacing line = GSpacing(bgra.step[0]);
    // Buffer band 0 is B, 1 G, 2 R: GeoTIFF bands 3, 2, 1.
    int band_map[3] = {3, 2, 1};
    if (GDALDatasetRasterIOEx(dataset_, GF_Write, 0, row0, cols, rows, data, cols, rows, GDT_Byte, 3,
                              band_map, 4, line, 1, nullptr) != CE_None) {
      fail("cannot write rows");
    }
    if (GDALRasterIOEx(mask_, GF_Write, 0, row0, cols, rows, data + 3, cols, rows, GDT_Byte, 4, line,
                       nullptr) != CE_None) {
      fail("cannot write the mask");
    }
    // The caller's bands are whole rows of tiles: write them out and drop
    // them from GDAL's block cache, which would otherwise keep up to
    // GDAL_CACHEMAX (5 % of the RAM) of them.
    GDALFlushCache(dataset_);
    checkQuiet();
  }

  // Overviews (when asked for), then closes the file.
  void finish() {
    if (options_.geotiff_overviews) {
      std::vector<int> levels;
      for (int f = 2; std::max(grid_.cols, grid_.rows) / (f / 2) > options_.geotiff_block_size; f *= 2) {
        levels.push_back(f);
      }
      if (!levels.empty() && GDALBuildOverviews(dataset_, "AVERAGE", int(levels.size()), levels.data(), 0,
                                                nullptr, nullptr, nullptr) != CE_None) {
        fail("cannot build overviews");
      }
    }
    dataset_.close();  // flushes the last tiles
    checkQuiet();
  }

 private:
  void setUtmCrs() {
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRSetAxisMappingStrategy(srs, OAMS_TRADITIONAL_GIS_ORDER);
    if (OSRImportFromEPSG(srs, (grid_.northern ? 32600 : 32700) + grid_.zone) != OGRERR_NONE) {
      // Without PROJ's database: the same CRS from its definition.
      CPLErrorReset();
      OSRSetWellKnownGeogCS(srs, "WGS84");
      OSRSetUTM(srs, grid_.zone, grid_.northern ? TRUE : FALSE);
      OSRAutoIdentifyEPSG(srs);
    }
    const CPLErr status = GDALSetSpatialRef(dataset_, srs);
    OSRDestroySpatialReference(srs);
    if (status != CE_None) fail("cannot set the CRS");
  }
  void checkQuiet() {
    if (quiet_.failed()) fail("GDAL failed");
  }
  [[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error("cannot write " + path_.string() + ": " + what +
                             (quiet_.failed() ? " (" + quiet_.message() + ")" : ""));
  }

  // Closes the dataset when the writer goes (also when its constructor throws).
  struct Dataset {
    GDALDatasetH handle = nullptr;
    ~Dataset() { close(); }
    void close() {
      if (handle != nullptr) GDALClose(handle);
      handle = nullptr;
    }
    operator GDALDatasetH() const { return handle; }
  };

  GdalQuiet quiet_;  // first member: alive while the dataset is
  std::filesystem::path path_;
  OrthoGrid grid_;
  RgbOrthoOptions options_;
  Dataset dataset_;
  GDALRasterBandH mask_ = nullptr;
};

}  // namespace

// ---- Verticals --------------------------------------------------------------

// The vertical of every pixel position as a ray, from a lattice of exact
// ones (see the header, "Method"): per node, the point of the vertical at
// W down = top_down and its unit downward direction.
struct RgbOrthoRenderer::Verticals {
  static constexpr double kMinSpacingM = 1.0;
  static constexpr int kMaxNodesPerSide = 256;

  Verticals(const OrthoGrid& grid, const UtmProjection& projection, double top_down, double bottom_down)
      : grid(grid), projection(projection), top_down(top_down), bottom_down(bottom_down) {
    const int extent_px = std::max(grid.cols, grid.rows) - 1;
    step_px = std::max(kMinSpacingM / grid.pixel_m, double(extent_px) / double(kMaxNodesPerSide - 2));
    node_cols = std::max(2, int(std::ceil((grid.cols - 1) / step_px)) + 1);
    node_rows = std::max(2, int(std::ceil((grid.rows - 1) / step_px)) + 1);
    origins.resize(std::size_t(node_cols) * node_rows);
    directions.resize(origins.size());
    for (int i = 0; i < node_rows; ++i) {
      for (int j = 0; j < node_cols; ++j) {
        const Ray ray = exact(j * step_px, i * step_px);
        origins[std::size_t(i) * node_cols + j] = ray.origin;
        directions[std::size_t(i) * node_cols + j] = ray.direction;
      }
    }
  }

  // GeographicLib at the pixel position (col, row).
  Ray exact(double col, double row) const {
    const Eigen::Vector2d en = grid.utmOfPixel({col, row});
    Ray ray;
    ray.origin = projection.utmToNed(en.x(), en.y(), top_down);
    ray.direction = (projection.utmToNed(en.x(), en.y(), top_down + 1.0) - ray.origin).normalized();
    return ray;
  }

  Ray at(double col, double row) const {
    const double x = col / step_px, y = row / step_px;
    Ray ray;
    if (x >= 0.0 && y >= 0.0 && x <= node_cols - 1 && y <= node_rows - 1) {
      const int j = std::min(int(x), node_cols - 2), i = std::min(int(y), node_rows - 2);
      const double a = y - i, b = x - j;
      const std::size_t k = std::size_t(i) * node_cols + j;
      auto bilinear = [&](const std::vector<Eigen::Vector3d>& v) -> Eigen::Vector3d {
        return (1 - a) * ((1 - b) * v[k] + b * v[k + 1]) +
               a * ((1 - b) * v[k + node_cols] + b * v[k + node_cols + 1]);
      };
      ray.origin = bilinear(origins);
      ray.direction = bilinear(directions).normalized();
    } else {
      ray = exact(col, row);  // off the lattice: slow, still exact
    }
    // From the top of the box to its bottom, measured along the vertical.
    ray.t_near = 0.0;
    ray.t_far = (bottom_down - top_down) / ray.direction.z();
    return ray;
  }

  OrthoGrid grid;
  UtmProjection projection;
  double top_down, bottom_down;
  double step_px = 1.0;
  int node_cols = 0, node_rows = 0;
  std::vector<Eigen::Vector3d> origins;     // [i * node_cols + j]: pixel (j step, i step)
  std::vector<Eigen::Vector3d> directions;  // unit, downwards
};

// ---- Options, report --------------------------------------------------------

void RgbOrthoOptions::validate() const {
  require(margin_m > 0.0 && std::isfinite(margin_m), "margin_m", "a margin > 0 m");
  require(band_pixels >= 1, "band_pixels", "at least 1 pixel");
  require(geotiff_block_size >= 16 && geotiff_block_size <= 4096 && geotiff_block_size % 16 == 0,
          "geotiff_block_size", "a multiple of 16 in [16, 4096]");
  const std::string c = upper(geotiff_compression);
  require(c == "DEFLATE" || c == "ZSTD" || c == "LZW" || c == "LZMA" || c == "NONE", "geotiff_compression",
          "DEFLATE, ZSTD, LZW, LZMA or NONE, got '" + geotiff_compression + "'");
}

std::string RgbOrthoReport::summary() const {
  std::ostringstream out;
  out.precision(3);
  out << std::fixed;
  out << "RGB ortho-image: " << grid.cols << " x " << grid.rows << " pixels of " << grid.pixel_m * 1000.0
      << " mm, " << hits << " of " << pixels << " show the mesh (" << coverage() * 100.0 << " %), "
      << bands << " band(s) of " << band_rows << " rows; time: setup " << setup_seconds << " s, render "
      << render_seconds << " s, write " << write_seconds << " s; peak memory " << peak_memory_mb << " MB";
  return out.str();
}

// ---- Renderer ---------------------------------------------------------------

RgbOrthoRenderer::RgbOrthoRenderer(const PlyMesh& mesh, const OrthoGrid& grid,
                                   const UtmProjection& projection, double margin_m)
    : grid_(grid),
      colors_(mesh.colors),
      own_caster_(std::make_unique<MeshRayCaster>(mesh.vertices, mesh.triangles)),
      caster_(own_caster_.get()) {
  setUp(mesh, projection, margin_m);
}

RgbOrthoRenderer::RgbOrthoRenderer(const PlyMesh& mesh, const MeshRayCaster& caster, const OrthoGrid& grid,
                                   const UtmProjection& projection, double margin_m)
    : grid_(grid), colors_(mesh.colors), caster_(&caster) {
  if (caster.vertices().size() != mesh.vertices.size() || caster.triangles().size() != mesh.triangles.size()) {
    throw std::invalid_argument("RgbOrthoRenderer: the ray caster holds " + std::to_string(caster.vertices().size()) +
                                " vertices and " + std::to_string(caster.triangles().size()) +
                                " triangles, the mesh " + std::to_string(mesh.vertices.size()) + " and " +
                                std::to_string(mesh.triangles.size()));
  }
  setUp(mesh, projection, margin_m);
}

void RgbOrthoRenderer::setUp(const PlyMesh& mesh, const UtmProjection& projection, double margin_m) {
  const OrthoGrid& grid = grid_;
  if (mesh.colors.size() != mesh.vertices.size()) {
    throw std::invalid_argument("RgbOrthoRenderer: the mesh needs one colour per vertex, got " +
                                std::to_string(mesh.colors.size()) + " colours for " +
                                std::to_string(mesh.vertices.size()) + " vertices");
  }
  if (grid.cols < 1 || grid.rows < 1 || !(grid.pixel_m > 0.0)) {
    throw std::invalid_argument("RgbOrthoRenderer: the grid has no pixels");
  }
  if (projection.zone() != grid.zone || projection.northernHemisphere() != grid.northern) {
    throw std::invalid_argument("RgbOrthoRenderer: the projection is UTM zone " +
                                std::to_string(projection.zone()) + (projection.northernHemisphere() ? "N" : "S") +
                                ", the grid " + std::to_string(grid.zone) + (grid.northern ? "N" : "S"));
  }
  if (!(margin_m > 0.0) || !std::isfinite(margin_m)) {
    throw std::invalid_argument("RgbOrthoRenderer: the margin must be > 0 m");
  }
  const Eigen::AlignedBox3d box = caster_->bounds();
  verticals_ = std::make_unique<Verticals>(grid, projection, box.min().z() - margin_m, box.max().z() + margin_m);
}

RgbOrthoRenderer::~RgbOrthoRenderer() = default;

Ray RgbOrthoRenderer::verticalRay(double col, double row) const { return verticals_->at(col, row); }

void RgbOrthoRenderer::checkWindow(int col0, int row0, int cols, int rows) const {
  if (cols < 1 || rows < 1 || col0 < 0 || row0 < 0 || cols > grid_.cols - col0 || rows > grid_.rows - row0) {
    throw std::invalid_argument("RgbOrthoRenderer::render: window " + std::to_string(cols) + " x " +
                                std::to_string(rows) + " at (" + std::to_string(col0) + ", " +
                                std::to_string(row0) + ") is empty or leaves the " + std::to_string(grid_.cols) +
                                " x " + std::to_string(grid_.rows) + " grid");
  }
}

RgbOrthoPatch RgbOrthoRenderer::render(int col0, int row0, int cols, int rows) const {
  RgbOrthoPatch patch;
  render(col0, row0, cols, rows, patch);
  return patch;
}

void RgbOrthoRenderer::render(int col0, int row0, int cols, int rows, RgbOrthoPatch& patch) const {
  checkWindow(col0, row0, cols, rows);
  patch.col0 = col0;
  patch.row0 = row0;
  patch.bgra.create(rows, cols, CV_8UC4);
  patch.p_W.resize(std::size_t(rows) * cols);
  renderInto(col0, row0, patch.bgra, patch.p_W.data());
}

void RgbOrthoRenderer::renderColours(int col0, int row0, int cols, int rows, cv::Mat& bgra) const {
  checkWindow(col0, row0, cols, rows);
  bgra.create(rows, cols, CV_8UC4);
  renderInto(col0, row0, bgra, nullptr);
}

void RgbOrthoRenderer::renderInto(int col0, int row0, cv::Mat& bgra, Eigen::Vector3d* p_W) const {
  const int cols = bgra.cols;
  const std::vector<Eigen::Vector3i>& triangles = caster_->triangles();
  const Eigen::Vector3d no_point = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  // Rays and hits of one image row per thread, allocated once per call.
  struct RowBuffers {
    std::vector<Ray> rays;
    std::vector<RayHit> hits;
  };
  tbb::enumerable_thread_specific<RowBuffers> buffers;

  // One image row a batch: coherent rays for Embree's streams.
  tbb::parallel_for(tbb::blocked_range<int>(0, bgra.rows), [&](const tbb::blocked_range<int>& range) {
    RowBuffers& buffer = buffers.local();
    buffer.rays.resize(cols);
    buffer.hits.resize(cols);
    const std::vector<Ray>& rays = buffer.rays;
    for (int r = range.begin(); r < range.end(); ++r) {
      for (int c = 0; c < cols; ++c) buffer.rays[c] = verticals_->at(col0 + c, row0 + r);
      caster_->intersect(std::span<const Ray>(rays), std::span<RayHit>(buffer.hits));
      auto* out = bgra.ptr<cv::Vec4b>(r);
      Eigen::Vector3d* points = p_W != nullptr ? p_W + std::size_t(r) * cols : nullptr;
      for (int c = 0; c < cols; ++c) {
        const RayHit& hit = buffer.hits[c];
        if (!hit.hit()) {
          out[c] = cv::Vec4b(0, 0, 0, 0);
          if (points != nullptr) points[c] = no_point;
          continue;
        }
        const Eigen::Vector3i& t = triangles[hit.triangle];
        const Eigen::Vector3d colour = (1.0 - hit.u - hit.v) * colors_[t[0]].cast<double>() +
                                       hit.u * colors_[t[1]].cast<double>() +
                                       hit.v * colors_[t[2]].cast<double>();
        auto byte = [](double value) { return std::uint8_t(std::lround(std::clamp(value, 0.0, 255.0))); };
        out[c] = cv::Vec4b(byte(colour.z()), byte(colour.y()), byte(colour.x()), 255);
        if (points != nullptr) points[c] = rays[c].origin + hit.distance * rays[c].direction;
      }
    }
  });
}

// ---- Writer -----------------------------------------------------------------

RgbOrthoReport writeRgbOrtho(const RgbOrthoRenderer& renderer, const std::filesystem::path& out_folder,
                             const RgbOrthoOptions& options) {
  options.validate();
  const OrthoGrid& grid = renderer.grid();
  RgbOrthoReport report;
  report.grid = grid;
  report.pixels = grid.pixelCount();
  std::int64_t band_rows = std::max<std::int64_t>(options.band_pixels / grid.cols, 1);
  if (options.write_geotiff) {
    // Whole rows of GeoTIFF tiles, so that each tile is compressed and written once.
    const int tile = options.geotiff_block_size;
    band_rows = (band_rows + tile - 1) / tile * tile;
  }
  report.band_rows = int(std::min<std::int64_t>(band_rows, grid.rows));
  std::filesystem::create_directories(out_folder);

  std::optional<AtomicFile> tif_file;
  std::optional<RgbGeoTiff> tif;
  if (options.write_geotiff) {
    tif_file.emplace(out_folder / "rgb_ortho.tif", AtomicFile::Mode::byPath);
    tif.emplace(tif_file->partialPath(), grid, options);
  }
  cv::Mat png;
  if (options.write_png) png = cv::Mat(grid.rows, grid.cols, CV_8UC4);

  // One band's colours, reused from band to band (no points: only the
  // refinement needs them, through RgbOrthoRenderer::render).
  cv::Mat band_buffer(report.band_rows, grid.cols, CV_8UC4);
  for (int row0 = 0; row0 < grid.rows; row0 += report.band_rows) {
    const int rows = std::min(report.band_rows, grid.rows - row0);
    Clock::time_point start = Clock::now();
    cv::Mat band = band_buffer.rowRange(0, rows);
    renderer.renderColours(0, row0, grid.cols, rows, band);
    for (int r = 0; r < rows; ++r) {
      const auto* row = band.ptr<cv::Vec4b>(r);
      for (int c = 0; c < grid.cols; ++c) report.hits += row[c][3] != 0;
    }
    report.render_seconds += secondsSince(start);
    ++report.bands;
    start = Clock::now();
    if (tif) tif->writeRows(row0, band);
    if (!png.empty()) band.copyTo(png.rowRange(row0, row0 + rows));
    report.write_seconds += secondsSince(start);
  }

  const Clock::time_point start = Clock::now();
  if (tif) {
    tif->finish();
    tif.reset();
    tif_file->commit();
    report.tif = tif_file->path();
  }
  if (!png.empty()) {
    AtomicFile file(out_folder / "rgb_ortho.png");
    std::vector<std::uint8_t> encoded;
    if (!cv::imencode(".png", png, encoded)) {
      throw std::runtime_error("cannot write " + file.path().string() + ": PNG encoding failed");
    }
    png.release();
    file.stream().write(reinterpret_cast<const char*>(encoded.data()), std::streamsize(encoded.size()));
    file.commit();
    report.png = file.path();
  }
  report.write_seconds += secondsSince(start);
  report.peak_memory_mb = peakResidentMemoryMb();
  return report;
}

RgbOrthoReport writeRgbOrtho(const PlyMesh& mesh, const OrthoGrid& grid, const UtmProjection& projection,
                             const std::filesystem::path& out_folder, const RgbOrthoOptions& options) {
  options.validate();  // before the BVH is built
  const Clock::time_point start = Clock::now();
  const MeshRayCaster caster(mesh.vertices, mesh.triangles);
  const double bvh_seconds = secondsSince(start);
  RgbOrthoReport report = writeRgbOrtho(mesh, caster, grid, projection, out_folder, options);
  report.setup_seconds += bvh_seconds;
  return report;
}

RgbOrthoReport writeRgbOrtho(const PlyMesh& mesh, const MeshRayCaster& caster, const OrthoGrid& grid,
                             const UtmProjection& projection, const std::filesystem::path& out_folder,
                             const RgbOrthoOptions& options) {
  options.validate();
  const Clock::time_point start = Clock::now();
  const RgbOrthoRenderer renderer(mesh, caster, grid, projection, options.margin_m);
  const double setup_seconds = secondsSince(start);
  RgbOrthoReport report = writeRgbOrtho(renderer, out_folder, options);
  report.setup_seconds = setup_seconds;
  return report;
}

}  // namespace hsmap
