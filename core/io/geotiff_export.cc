#include "core/io/geotiff_export.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal.h>
#include <gdal_vrt.h>
#include <ogr_srs_api.h>

#include "core/io/atomic_file.h"
#include "core/io/envi_header.h"
#include "core/io/envi_ignore_value.h"
#include "core/io/envi_reader.h"
#include "core/util/input_error.h"

namespace hsmap {
namespace {

constexpr const char* kExpectedMapInfo =
    "{UTM, 1, 1, easting, northing, px, px, zone, North|South, WGS-84, units=Meters}";

std::string lowercase(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Shortest text that reads back to the same double (450.2, not 450.199997).
std::string formatNumber(double value) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

// The unit symbol for ENVI's `wavelength units` (nm when absent, as in
// DATASET.md); empty for ENVI's unit-less "Unknown" and "Index".
std::string wavelengthSymbol(const std::string& units) {
  const std::string u = lowercase(units);
  if (u.empty() || u == "nanometers" || u == "nanometer" || u == "nm") return "nm";
  if (u == "micrometers" || u == "micrometer" || u == "microns" || u == "micron" || u == "um") return "um";
  if (u == "millimeters" || u == "millimeter" || u == "mm") return "mm";
  if (u == "unknown" || u == "index") return "";
  return units;
}

bool isFloat(EnviDataType type) { return type == EnviDataType::float32 || type == EnviDataType::float64; }

// The checks of the contract on `map info`: UTM on WGS-84 in metres. GDAL's
// ENVI driver would read a datum-less UTM map info as NAD27, hence the
// explicit datum test (absent counts as WGS-84: hsmap writes no other).
const EnviMapInfo& requireUtmMapInfo(const EnviHeader& header, const std::filesystem::path& hdr) {
  const std::string where = InputError::atKey("map info");
  const std::string required = "required to export a GeoTIFF: expected " + std::string(kExpectedMapInfo);
  if (!header.map_info) throw InputError(hdr, where, required + ", found none");
  const EnviMapInfo& info = *header.map_info;
  if (lowercase(info.projection) != "utm") {
    throw InputError(hdr, where, required + ", found projection '" + info.projection + "'");
  }
  const std::string datum = lowercase(info.datum);
  if (!datum.empty() && datum != "wgs-84" && datum != "wgs84" && datum != "wgs 84") {
    throw InputError(hdr, where, required + ", found datum '" + info.datum + "'");
  }
  const std::string units = lowercase(info.units);
  if (!units.empty() && units != "meters" && units != "meter" && units != "metres" && units != "m") {
    throw InputError(hdr, where, required + ", found units '" + info.units + "'");
  }
  if (!(info.pixel_size_x > 0) || !(info.pixel_size_y > 0)) {
    throw InputError(hdr, where,
                     "expected positive pixel sizes, found " + formatNumber(info.pixel_size_x) + " and " +
                         formatNumber(info.pixel_size_y));
  }
  // readEnviHeader already holds a UTM zone to 1..60; kept for headers built in code.
  if (info.zone < 1 || info.zone > 60) {
    throw InputError(hdr, where, "expected a UTM zone 1..60, found " + std::to_string(info.zone));
  }
  return info;
}


// While alive, GDAL's errors on this thread are collected instead of printed
// (CPLPushErrorHandlerEx is per thread), and GDAL writes no .aux.xml side
// files (which would otherwise follow the .partial name, or touch the ENVI
// folder).
class GdalErrorCapture {
 public:
  GdalErrorCapture() {
    if (const char* pam = CPLGetThreadLocalConfigOption("GDAL_PAM_ENABLED", nullptr)) previous_pam_ = pam;
    CPLErrorReset();
    CPLPushErrorHandlerEx(&GdalErrorCapture::handle, this);
    CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO");
  }
  ~GdalErrorCapture() {
    CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", previous_pam_ ? previous_pam_->c_str() : nullptr);
    CPLPopErrorHandler();
  }
  GdalErrorCapture(const GdalErrorCapture&) = delete;
  GdalErrorCapture& operator=(const GdalErrorCapture&) = delete;

  bool failed() const { return !messages_.empty(); }
  // The failures so far, "; "-separated ("unknown GDAL error" when a call
  // failed without saying why).
  std::string message() const {
    std::string out;
    for (const std::string& m : messages_) out += (out.empty() ? "" : "; ") + m;
    return out.empty() ? "unknown GDAL error" : out;
  }

 private:
  static void CPL_STDCALL handle(CPLErr level, CPLErrorNum, const char* message) {
    if (level != CE_Failure && level != CE_Fatal) return;  // warnings and debug output are dropped
    auto* self = static_cast<GdalErrorCapture*>(CPLGetErrorHandlerUserData());
    const std::string text = message != nullptr ? message : "";
    if (self->messages_.size() < 8 &&
        std::find(self->messages_.begin(), self->messages_.end(), text) == self->messages_.end()) {
      self->messages_.push_back(text);
    }
  }

  std::vector<std::string> messages_;
  std::optional<std::string> previous_pam_;  // the caller's thread-local setting, restored
};

struct GdalDatasetCloser {
  void operator()(GDALDatasetH dataset) const {
    if (dataset != nullptr) GDALClose(dataset);
  }
};
using GdalDataset = std::unique_ptr<std::remove_pointer_t<GDALDatasetH>, GdalDatasetCloser>;

struct SpatialReferenceDeleter {
  void operator()(OGRSpatialReferenceH srs) const { OSRDestroySpatialReference(srs); }
};

// WGS 84 / UTM zone `zone` North|South: EPSG:326zz / 327zz, with the EPSG
// code attached so that readers name the CRS rather than "unnamed".
std::unique_ptr<std::remove_pointer_t<OGRSpatialReferenceH>, SpatialReferenceDeleter> utmSpatialReference(
    int zone, bool north) {
  std::unique_ptr<std::remove_pointer_t<OGRSpatialReferenceH>, SpatialReferenceDeleter> srs(
      OSRNewSpatialReference(nullptr));
  OSRSetAxisMappingStrategy(srs.get(), OAMS_TRADITIONAL_GIS_ORDER);
  if (OSRImportFromEPSG(srs.get(), (north ? 32600 : 32700) + zone) != OGRERR_NONE) {
    // Without PROJ's database: the same CRS built from its definition.
    CPLErrorReset();
    OSRSetWellKnownGeogCS(srs.get(), "WGS84");
    OSRSetUTM(srs.get(), zone, north ? TRUE : FALSE);
    OSRAutoIdentifyEPSG(srs.get());
  }
  return srs;
}

// Removes the export's working files next to `partial` (the VRT and its
// overviews, below) and what GDAL may leave there when writing fails half-way.
void removeGdalLeftovers(const std::filesystem::path& partial) {
  for (const char* suffix : {".vrt", ".vrt.ovr", ".ovr.tmp", ".msk.ovr.tmp", ".aux.xml"}) {
    std::filesystem::path leftover = partial;
    leftover += suffix;
    std::error_code ignored;
    std::filesystem::remove(leftover, ignored);
  }
}

// GDAL's block cache is one per process and by default 5% of the RAM: every
// ENVI line the export reads stays in it until it is full (1.2 GB on a 24 GB
// machine). While any export runs the cache is capped at
// kExportBlockCacheBytes (the export reads each band's lines once per tile row
// of 512 lines, a few MB); the last export to finish restores the caller's
// limit. A lower limit set by the caller is kept.
constexpr GIntBig kExportBlockCacheBytes = GIntBig{64} << 20;

class BlockCacheLimit {
 public:
  BlockCacheLimit() {
    const std::lock_guard<std::mutex> lock(mutex());
    State& s = state();
    if (s.active++ == 0) {
      s.previous = GDALGetCacheMax64();
      if (s.previous > kExportBlockCacheBytes) GDALSetCacheMax64(kExportBlockCacheBytes);
    }
  }
  ~BlockCacheLimit() {
    const std::lock_guard<std::mutex> lock(mutex());
    State& s = state();
    if (--s.active == 0 && GDALGetCacheMax64() == std::min(s.previous, kExportBlockCacheBytes)) {
      GDALSetCacheMax64(s.previous);
    }
  }
  BlockCacheLimit(const BlockCacheLimit&) = delete;
  BlockCacheLimit& operator=(const BlockCacheLimit&) = delete;

 private:
  struct State {
    int active = 0;
    GIntBig previous = 0;
  };
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static State& state() {
    static State s;
    return s;
  }
};

// Overview decimation factors as GDAL's COG driver chooses them: halving
// until the image fits in one tile (600 x 4000 with 512 tiles: 2, 4, 8).
std::vector<int> overviewFactors(int cols, int rows, int block_size) {
  std::vector<int> factors;
  for (int f = 2; (cols + f / 2 - 1) / (f / 2) > block_size || (rows + f / 2 - 1) / (f / 2) > block_size;
       f *= 2) {
    factors.push_back(f);
  }
  return factors;
}

// A GDAL progress callback that hands memory freed by GDAL back to the
// system every 16 calls (GDAL calls it per tile or chunk of lines). glibc's
// malloc otherwise keeps it in its heaps: after a large block is freed (the
// GTiff copy allocates a buffer for one tile of all bands), its mmap
// threshold rises, so the 1 MB tiles of the block cache and of the
// compression threads come from heaps that fragment and grow with the image.
// Peak RSS for the 2 GB ortho of docs/BENCHMARKS.md: 807 MB without the trim,
// about 250 MB with it; a few % more system time.
int CPL_STDCALL trimFreedMemory(double, const char*, void* calls) {
#ifdef __GLIBC__
  if (++*static_cast<int*>(calls) % 16 == 0) malloc_trim(0);
#endif
  return TRUE;
}

// GDAL's TIFF predictor for `type`: floating-point (3) or horizontal
// differencing (2).
const char* predictorFor(EnviDataType type) { return isFloat(type) ? "3" : "2"; }

}  // namespace

void GeoTiffExportOptions::validate() const {
  if (block_size < 16 || block_size > 4096 || block_size % 16 != 0) {
    throw std::invalid_argument(
        "GeoTiffExportOptions.block_size must be a multiple of 16 in [16, 4096], got " +
        std::to_string(block_size));
  }
  static const std::vector<std::string> kCodecs = {"DEFLATE", "ZSTD", "LZW", "LZMA", "NONE"};
  if (std::find(kCodecs.begin(), kCodecs.end(), compression) == kCodecs.end()) {
    throw std::invalid_argument(
        "GeoTiffExportOptions.compression must be one of DEFLATE, ZSTD, LZW, LZMA, NONE, got '" +
        compression + "'");
  }
  static const std::vector<std::string> kResamplings = {"NEAREST",     "AVERAGE", "BILINEAR", "CUBIC",
                                                        "CUBICSPLINE", "LANCZOS", "MODE",     "RMS"};
  if (std::find(kResamplings.begin(), kResamplings.end(), overview_resampling) == kResamplings.end()) {
    throw std::invalid_argument(
        "GeoTiffExportOptions.overview_resampling must be one of NEAREST, AVERAGE, BILINEAR, CUBIC, "
        "CUBICSPLINE, LANCZOS, MODE, RMS, got '" +
        overview_resampling + "'");
  }
  if (threads < 0) {
    throw std::invalid_argument("GeoTiffExportOptions.threads must be >= 0 (0: every CPU), got " +
                                std::to_string(threads));
  }
}

void exportEnviToCog(const std::filesystem::path& envi_header, const std::filesystem::path& tif_path,
                     const GeoTiffExportOptions& options) {
  options.validate();
  // hsmap's reader checks the header, finds the data file and checks its
  // size: GDAL's ENVI driver reads a truncated file as zeros without a word.
  const EnviReader reader(envi_header);
  const EnviHeader& header = reader.header();
  const std::filesystem::path& data_path = reader.dataPath();
  const EnviMapInfo& map = requireUtmMapInfo(header, envi_header);
  // NaN (what hsmap writes) reads as none: float data get NaN nodata below.
  const std::optional<float> ignore_value = enviDataIgnoreValue(header, envi_header);

  registerGdalDrivers();
  GdalErrorCapture errors;

  // GDAL's ENVI driver opens the data file (it refuses the .hdr) and finds the
  // header next to it; the allowed-driver list keeps other raw-file drivers
  // from claiming a .raw file.
  const char* const envi_only[] = {"ENVI", nullptr};
  GdalDataset source(
      GDALOpenEx(std::filesystem::absolute(data_path).c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, envi_only,
                 nullptr, nullptr));
  if (!source) {
    throw InputError(data_path, "", "GDAL's ENVI driver cannot read it: " + errors.message());
  }
  if (GDALGetRasterXSize(source.get()) != header.samples ||
      GDALGetRasterYSize(source.get()) != header.lines || GDALGetRasterCount(source.get()) != header.bands) {
    throw InputError(data_path, "",
                     "GDAL reads " + std::to_string(GDALGetRasterXSize(source.get())) + " x " +
                         std::to_string(GDALGetRasterYSize(source.get())) + " x " +
                         std::to_string(GDALGetRasterCount(source.get())) +
                         " (samples x lines x bands), but " + envi_header.string() + " says " +
                         std::to_string(header.samples) + " x " + std::to_string(header.lines) + " x " +
                         std::to_string(header.bands));
  }

  // A VRT that shows the ENVI bands with hsmap's georeferencing and band text
  // and nothing else (no ENVI metadata domains carried into the GeoTIFF).
  GdalDataset vrt(VRTCreate(header.samples, header.lines));
  const auto srs = utmSpatialReference(map.zone, map.north);
  GDALSetSpatialRef(vrt.get(), srs.get());
  double geo_transform[6] = {map.easting - (map.reference_pixel_x - 1.0) * map.pixel_size_x,
                             map.pixel_size_x,
                             0.0,
                             map.northing + (map.reference_pixel_y - 1.0) * map.pixel_size_y,
                             0.0,
                             -map.pixel_size_y};
  GDALSetGeoTransform(vrt.get(), geo_transform);
  const std::string symbol = wavelengthSymbol(header.wavelength_units);
  std::optional<double> nodata;
  if (ignore_value) nodata = *ignore_value;
  if (!nodata && isFloat(header.data_type)) nodata = std::numeric_limits<double>::quiet_NaN();

  for (int b = 0; b < header.bands; ++b) {
    GDALRasterBandH source_band = GDALGetRasterBand(source.get(), b + 1);
    VRTAddBand(vrt.get(), GDALGetRasterDataType(source_band), nullptr);
    GDALRasterBandH band = GDALGetRasterBand(vrt.get(), b + 1);
    VRTAddSimpleSource(band, source_band, 0, 0, header.samples, header.lines, 0, 0, header.samples,
                       header.lines, "near", VRT_NODATA_UNSET);
    if (nodata) GDALSetRasterNoDataValue(band, *nodata);
    if (!header.wavelength.empty()) {
      const std::string wavelength = formatNumber(header.wavelength[b]);
      GDALSetDescription(band, (symbol.empty() ? wavelength : wavelength + " " + symbol).c_str());
      GDALSetMetadataItem(band, "wavelength", wavelength.c_str(), nullptr);
      GDALSetMetadataItem(band, "wavelength_units",
                          (header.wavelength_units.empty() ? "Nanometers" : header.wavelength_units).c_str(),
                          nullptr);
    } else if (!header.band_names.empty()) {
      GDALSetDescription(band, header.band_names[b].c_str());
    }
    if (!header.fwhm.empty())
      GDALSetMetadataItem(band, "fwhm", formatNumber(header.fwhm[b]).c_str(), nullptr);
  }
  if (errors.failed()) {
    throw std::runtime_error("cannot prepare " + tif_path.string() + " from " + data_path.string() + ": " +
                             errors.message());
  }

  GDALDriverH vrt_driver = GDALGetDriverByName("VRT");
  GDALDriverH gtiff = GDALGetDriverByName("GTiff");
  if (vrt_driver == nullptr || gtiff == nullptr) {
    throw std::runtime_error("cannot write " + tif_path.string() + ": this GDAL has no VRT or GTiff driver");
  }
  const std::string threads = options.threads == 0 ? "ALL_CPUS" : std::to_string(options.threads);
  const bool predictor = options.predictor && options.compression != "NONE";
  const std::string block = std::to_string(options.block_size);

  AtomicFile file(tif_path, AtomicFile::Mode::byPath);
  struct Leftovers {
    std::filesystem::path partial;
    ~Leftovers() { removeGdalLeftovers(partial); }
  } leftovers{file.partialPath()};
  const BlockCacheLimit cache_limit;
  int progress_calls = 0;  // trimFreedMemory's count
  // No multi-threaded decoding of the overviews' working file (which
  // GDAL_NUM_THREADS, even from the environment, would turn on): GDAL 3.6
  // fails on band-interleaved files of many bands there ("Bad value 210 for
  // ExtraSamples tag"), in worker threads whose errors no one sees. Compression
  // keeps its threads (NUM_THREADS below).
  const CPLConfigOptionSetter single_threaded_reads("GDAL_NUM_THREADS", "1", false);

  // The overviews, made before the GeoTIFF as GDAL's COG driver does, into a
  // working file `<partial>.vrt.ovr`: GDAL builds external overviews only for
  // a dataset opened from a file, hence the VRT written as `<partial>.vrt`.
  // Band-interleaved, ZSTD level 1 (fast; read back once; DEFLATE level 1
  // where this GDAL has no ZSTD). AVERAGE and
  // the other resamplings skip nodata pixels.
  GdalDataset source_for_copy;
  std::vector<int> factors;
  if (options.overviews) factors = overviewFactors(header.samples, header.lines, options.block_size);
  if (!factors.empty()) {
    std::filesystem::path vrt_path = file.partialPath();
    vrt_path += ".vrt";
    GdalDataset(GDALCreateCopy(vrt_driver, vrt_path.c_str(), vrt.get(), FALSE, nullptr, nullptr, nullptr));
    const char* const vrt_only[] = {"VRT", nullptr};
    source_for_copy.reset(
        GDALOpenEx(vrt_path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, vrt_only, nullptr, nullptr));
    if (!source_for_copy) {
      throw std::runtime_error("cannot write " + tif_path.string() + ": " + errors.message());
    }
    // GDAL takes an overview tile size only as a power of two >= 64.
    const bool power_of_two_block =
        (options.block_size & (options.block_size - 1)) == 0 && options.block_size >= 64;
    const char* codecs = GDALGetMetadataItem(gtiff, GDAL_DMD_CREATIONOPTIONLIST, nullptr);
    const bool zstd = codecs != nullptr && std::string_view(codecs).find("ZSTD") != std::string_view::npos;
    const CPLConfigOptionSetter ovr_compress("COMPRESS_OVERVIEW", zstd ? "ZSTD" : "DEFLATE", false);
    const CPLConfigOptionSetter ovr_level(zstd ? "ZSTD_LEVEL_OVERVIEW" : "ZLEVEL_OVERVIEW", "1", false);
    const CPLConfigOptionSetter ovr_interleave("INTERLEAVE_OVERVIEW", "BAND", false);
    const CPLConfigOptionSetter ovr_bigtiff("BIGTIFF_OVERVIEW", "IF_SAFER", false);
    const CPLConfigOptionSetter ovr_block("GDAL_TIFF_OVR_BLOCKSIZE",
                                          power_of_two_block ? block.c_str() : nullptr, false);
    if (GDALBuildOverviews(source_for_copy.get(), options.overview_resampling.c_str(),
                           static_cast<int>(factors.size()), factors.data(), 0, nullptr, trimFreedMemory,
                           &progress_calls) != CE_None ||
        errors.failed()) {
      throw std::runtime_error("cannot write " + tif_path.string() + ": " + errors.message());
    }
  }

  // The GeoTIFF: GTiff with COPY_SRC_OVERVIEWS writes the IFDs first, then
  // the overviews' tiles (smallest first), then the full-resolution tiles,
  // i.e. a cloud-optimized layout (GDAL's validate_cloud_optimized_geotiff.py
  // accepts it). Band-interleaved, unlike GDAL 3.6's COG driver (always
  // pixel-interleaved): a 512 x 512 tile of 211 float bands would be 221 MB to
  // buffer and compress per tile (GBs of RSS with several threads), and a GIS
  // showing three bands would decode all 211.
  CPLStringList creation;
  creation.SetNameValue("TILED", "YES");
  creation.SetNameValue("BLOCKXSIZE", block.c_str());
  creation.SetNameValue("BLOCKYSIZE", block.c_str());
  creation.SetNameValue("INTERLEAVE", "BAND");
  creation.SetNameValue("COMPRESS", options.compression.c_str());
  if (predictor) creation.SetNameValue("PREDICTOR", predictorFor(header.data_type));
  creation.SetNameValue("COPY_SRC_OVERVIEWS", "YES");
  creation.SetNameValue("NUM_THREADS", threads.c_str());
  // A compressed hyperspectral ortho can pass 4 GB; IF_NEEDED would only see
  // that for uncompressed data.
  creation.SetNameValue("BIGTIFF", "IF_SAFER");
  // The overviews copied into the GeoTIFF are compressed like the image.
  const CPLConfigOptionSetter ovr_compress("COMPRESS_OVERVIEW", options.compression.c_str(), false);
  const CPLConfigOptionSetter ovr_predictor("PREDICTOR_OVERVIEW",
                                            predictor ? predictorFor(header.data_type) : "1", false);
  {
    GDALDatasetH copied_from = source_for_copy ? source_for_copy.get() : vrt.get();
    GdalDataset written(GDALCreateCopy(gtiff, file.partialPath().c_str(), copied_from, FALSE, creation.List(),
                                       trimFreedMemory, &progress_calls));
    if (!written) {
      throw std::runtime_error("cannot write " + tif_path.string() + ": " + errors.message());
    }
  }  // closing flushes the last tiles: failures show in `errors`
  if (errors.failed()) {
    throw std::runtime_error("cannot write " + tif_path.string() + ": " + errors.message());
  }
  source_for_copy.reset();
  removeGdalLeftovers(file.partialPath());
  file.commit();
}

void registerGdalDrivers() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

}  // namespace hsmap
