#include "core/io/geotiff_export.h"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <gtest/gtest.h>

#include "core/io/envi_header.h"
#include "core/io/envi_writer.h"
#include "tests/support/expect_input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

constexpr int kSamples = 40, kLines = 30, kBands = 3;
const std::vector<double> kWavelengths = {450.2, 550, 650.75};

// Distinct values per (line, band, sample), NaN on a diagonal pattern and in
// a corner block (the empty parts of an ortho-image).
float pixelValue(int l, int b, int s) {
  if ((l + 2 * s) % 7 == 0 || (l < 5 && s < 6)) return std::nanf("");
  return static_cast<float>(100 * b + l) + 0.01f * static_cast<float>(s);
}

EnviMapInfo utmMapInfo(int zone, bool north) {
  EnviMapInfo map;
  map.projection = "UTM";
  map.easting = 431234.5;
  map.northing = north ? 4761020.25 : 7456789.75;
  map.pixel_size_x = 0.02;
  map.pixel_size_y = 0.02;
  map.zone = zone;
  map.north = north;
  map.datum = "WGS-84";
  map.units = "Meters";
  return map;
}

EnviHeader orthoHeader(std::optional<EnviMapInfo> map, EnviInterleave interleave = EnviInterleave::bsq) {
  EnviHeader header;
  header.samples = kSamples;
  header.lines = kLines;
  header.bands = kBands;
  header.data_type = EnviDataType::float32;
  header.interleave = interleave;
  header.wavelength_units = "Nanometers";
  header.wavelength = kWavelengths;
  header.map_info = std::move(map);
  header.description = "hsmap hyperspectral ortho-image";
  header.other_fields.emplace_back("data ignore value", "nan");
  return header;
}

// Writes the image with hsmap's own ENVI writer; returns the header path.
std::filesystem::path writeOrtho(const TempFolder& dir, const EnviHeader& header) {
  EnviWriter writer(dir / "ortho.hdr", header);
  std::vector<float> line(static_cast<std::size_t>(kSamples) * kBands);
  for (int l = 0; l < kLines; ++l) {
    for (int b = 0; b < kBands; ++b) {
      for (int s = 0; s < kSamples; ++s) line[b * kSamples + s] = pixelValue(l, b, s);
    }
    writer.writeLine(line.data());
  }
  writer.finish();
  return dir / "ortho.hdr";
}

struct DatasetCloser {
  void operator()(GDALDataset* dataset) const { GDALClose(dataset); }
};
using Dataset = std::unique_ptr<GDALDataset, DatasetCloser>;

Dataset openWithGdal(const std::filesystem::path& path, const char* driver) {
  GDALAllRegister();
  const char* const drivers[] = {driver, nullptr};
  return Dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers));
}

std::set<std::string> filesIn(const TempFolder& dir) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

// Every pixel of every band equals pixelValue, NaN exactly where it is NaN.
void expectPixels(GDALDataset& dataset) {
  ASSERT_EQ(dataset.GetRasterCount(), kBands);
  for (int b = 0; b < kBands; ++b) {
    std::vector<float> plane(static_cast<std::size_t>(kSamples) * kLines);
    ASSERT_EQ(dataset.GetRasterBand(b + 1)->RasterIO(GF_Read, 0, 0, kSamples, kLines, plane.data(), kSamples,
                                                     kLines, GDT_Float32, 0, 0),
              CE_None);
    int mismatches = 0;
    for (int l = 0; l < kLines; ++l) {
      for (int s = 0; s < kSamples; ++s) {
        const float expected = pixelValue(l, b, s);
        const float actual = plane[l * kSamples + s];
        const bool same = std::isnan(expected) ? std::isnan(actual) : actual == expected;
        if (!same && ++mismatches <= 5) {
          ADD_FAILURE() << "band " << b << " line " << l << " sample " << s << ": " << actual << ", expected "
                        << expected;
        }
      }
    }
    EXPECT_EQ(mismatches, 0) << "band " << b;
  }
}

void expectGeoTransform(GDALDataset& dataset, double x0, double y0, double px) {
  double gt[6] = {};
  ASSERT_EQ(dataset.GetGeoTransform(gt), CE_None);
  EXPECT_DOUBLE_EQ(gt[0], x0);
  EXPECT_DOUBLE_EQ(gt[1], px);
  EXPECT_EQ(gt[2], 0.0);
  EXPECT_DOUBLE_EQ(gt[3], y0);
  EXPECT_EQ(gt[4], 0.0);
  EXPECT_DOUBLE_EQ(gt[5], -px);  // north-up: y falls as the row grows
}

void expectSameCrsAsEpsg(GDALDataset& dataset, int epsg) {
  const OGRSpatialReference* srs = dataset.GetSpatialRef();
  ASSERT_NE(srs, nullptr);
  OGRSpatialReference expected;
  ASSERT_EQ(expected.importFromEPSG(epsg), OGRERR_NONE);
  EXPECT_TRUE(srs->IsSame(&expected)) << "not EPSG:" << epsg;
}

std::string metadataItem(GDALMajorObject& object, const char* name, const char* domain = nullptr) {
  const char* value = object.GetMetadataItem(name, domain);
  return value != nullptr ? value : "<absent>";
}

// The offsets of the IFDs of a little-endian TIFF or BigTIFF, in chain order.
std::vector<std::uint64_t> ifdOffsets(const std::filesystem::path& tif) {
  const std::string bytes = TempFolder::read(tif);
  const auto read = [&](std::uint64_t at, int size) {
    std::uint64_t value = 0;
    for (int i = size - 1; i >= 0; --i) value = value << 8 | static_cast<unsigned char>(bytes.at(at + i));
    return value;
  };
  if (bytes.size() < 16 || bytes.compare(0, 2, "II") != 0) return {};
  const bool big = read(2, 2) == 43;
  std::vector<std::uint64_t> offsets;
  for (std::uint64_t at = big ? read(8, 8) : read(4, 4); at != 0 && offsets.size() < 64;) {
    offsets.push_back(at);
    const std::uint64_t entries = big ? read(at, 8) : read(at, 2);
    const std::uint64_t next_at = big ? at + 8 + 20 * entries : at + 2 + 12 * entries;
    at = big ? read(next_at, 8) : read(next_at, 4);
  }
  return offsets;
}

std::uint64_t firstTileOffset(GDALRasterBand& band) {
  const std::string offset = metadataItem(band, "BLOCK_OFFSET_0_0", "TIFF");
  return offset == "<absent>" ? 0 : std::stoull(offset);
}

// A cloud-optimized layout (as GDAL's COG driver and validator define it):
// one IFD per resolution, every IFD before the first tile, the overviews'
// tiles (smallest first) before the full-resolution ones; band-interleaved.
void expectCloudOptimizedLayout(const std::filesystem::path& path, GDALDataset& tif) {
  EXPECT_EQ(metadataItem(tif, "INTERLEAVE", "IMAGE_STRUCTURE"), "BAND");
  GDALRasterBand* band = tif.GetRasterBand(1);
  const int overviews = band->GetOverviewCount();
  const std::vector<std::uint64_t> ifds = ifdOffsets(path);
  ASSERT_EQ(ifds.size(), static_cast<std::size_t>(1 + overviews));
  std::vector<std::uint64_t> tiles = {firstTileOffset(*band)};  // full resolution, then overviews
  for (int i = 0; i < overviews; ++i) tiles.push_back(firstTileOffset(*band->GetOverview(i)));
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    ASSERT_GT(tiles[i], 0u) << "level " << i;
    for (std::uint64_t ifd : ifds) EXPECT_LT(ifd, tiles[i]) << "IFD after the tiles of level " << i;
    if (i > 0) {
      EXPECT_LT(tiles[i], tiles[i - 1]) << "level " << i << " after level " << i - 1;
    }
  }
}

TEST(GeoTiffExport, CogCarriesPixelsCrsGeoTransformNodataAndWavelengths) {
  TempFolder dir;
  const std::filesystem::path hdr = writeOrtho(dir, orthoHeader(utmMapInfo(31, true)));
  exportEnviToCog(hdr, dir / "ortho.tif");

  EXPECT_EQ(filesIn(dir), (std::set<std::string>{"ortho.hdr", "ortho.raw", "ortho.tif"}));
  const Dataset tif = openWithGdal(dir / "ortho.tif", "GTiff");
  ASSERT_NE(tif, nullptr);
  EXPECT_STREQ(tif->GetDriver()->GetDescription(), "GTiff");
  EXPECT_EQ(tif->GetRasterXSize(), kSamples);
  EXPECT_EQ(tif->GetRasterYSize(), kLines);
  EXPECT_EQ(tif->GetRasterCount(), kBands);
  expectPixels(*tif);
  expectGeoTransform(*tif, 431234.5, 4761020.25, 0.02);

  const OGRSpatialReference* srs = tif->GetSpatialRef();
  ASSERT_NE(srs, nullptr);
  ASSERT_NE(srs->GetAuthorityCode(nullptr), nullptr);
  EXPECT_STREQ(srs->GetAuthorityName(nullptr), "EPSG");
  EXPECT_STREQ(srs->GetAuthorityCode(nullptr), "32631");
  expectSameCrsAsEpsg(*tif, 32631);

  const char* const wavelengths[] = {"450.2", "550", "650.75"};
  for (int b = 0; b < kBands; ++b) {
    GDALRasterBand* band = tif->GetRasterBand(b + 1);
    EXPECT_EQ(band->GetRasterDataType(), GDT_Float32);
    int has_nodata = 0;
    const double nodata = band->GetNoDataValue(&has_nodata);
    EXPECT_TRUE(has_nodata) << "band " << b;
    EXPECT_TRUE(std::isnan(nodata)) << "band " << b << " nodata " << nodata;
    EXPECT_EQ(std::string(band->GetDescription()), std::string(wavelengths[b]) + " nm");
    EXPECT_EQ(metadataItem(*band, "wavelength"), wavelengths[b]);
    EXPECT_EQ(metadataItem(*band, "wavelength_units"), "Nanometers");
    int block_x = 0, block_y = 0;
    band->GetBlockSize(&block_x, &block_y);
    EXPECT_EQ(block_x, 512);
    EXPECT_EQ(block_y, 512);
  }
  expectCloudOptimizedLayout(dir / "ortho.tif", *tif);
  EXPECT_EQ(metadataItem(*tif, "COMPRESSION", "IMAGE_STRUCTURE"), "DEFLATE");
  EXPECT_EQ(metadataItem(*tif, "PREDICTOR", "IMAGE_STRUCTURE"), "3");  // floating-point predictor
  // Nothing of the ENVI driver's own metadata ("Band_1=...") is carried over.
  EXPECT_EQ(metadataItem(*tif, "Band_1"), "<absent>");
}

TEST(GeoTiffExport, SmallTilesGiveSeveralTilesAndAveragedOverviews) {
  TempFolder dir;
  const std::filesystem::path hdr = writeOrtho(dir, orthoHeader(utmMapInfo(31, true)));
  GeoTiffExportOptions options;
  options.block_size = 16;
  options.compression = "ZSTD";
  options.threads = 1;
  exportEnviToCog(hdr, dir / "ortho.tif", options);

  const Dataset tif = openWithGdal(dir / "ortho.tif", "GTiff");
  ASSERT_NE(tif, nullptr);
  expectPixels(*tif);
  expectCloudOptimizedLayout(dir / "ortho.tif", *tif);
  EXPECT_EQ(metadataItem(*tif, "COMPRESSION", "IMAGE_STRUCTURE"), "ZSTD");
  GDALRasterBand* band = tif->GetRasterBand(2);
  int block_x = 0, block_y = 0;
  band->GetBlockSize(&block_x, &block_y);
  EXPECT_EQ(block_x, 16);
  EXPECT_EQ(block_y, 16);
  // Halving until one tile holds the image: 40 x 30 -> 20 x 15 -> 10 x 8.
  ASSERT_EQ(band->GetOverviewCount(), 2);
  GDALRasterBand* overview = band->GetOverview(0);
  EXPECT_EQ(overview->GetXSize(), 20);
  EXPECT_EQ(overview->GetYSize(), 15);
  // Pixel (line 8..9, samples 10..11) of band 1 averages its four sources,
  // skipping NaN ones: (108.10, 108.11, 109.10, 109.11) minus (l + 2s) % 7 == 0.
  float value = 0;
  ASSERT_EQ(overview->RasterIO(GF_Read, 5, 4, 1, 1, &value, 1, 1, GDT_Float32, 0, 0), CE_None);
  double sum = 0;
  int count = 0;
  for (int l = 8; l < 10; ++l) {
    for (int s = 10; s < 12; ++s) {
      const float v = pixelValue(l, 1, s);
      if (!std::isnan(v)) {
        sum += v;
        ++count;
      }
    }
  }
  ASSERT_GT(count, 0);
  EXPECT_NEAR(value, sum / count, 1e-3);
}

// GDAL 3.6 decodes band-interleaved tiles of many bands wrongly in worker
// threads ("Bad value 11 for ExtraSamples tag") when GDAL_NUM_THREADS is set,
// and worker threads report to the global error handler only: the export
// reads its overviews' working file on its own thread whatever the
// configuration says.
std::atomic<int> worker_errors{0};
void CPL_STDCALL countErrors(CPLErr level, CPLErrorNum, const char*) {
  if (level == CE_Failure || level == CE_Fatal) ++worker_errors;
}

TEST(GeoTiffExport, ManyBandsUnderGdalNumThreadsGiveNoHiddenErrorsAndRightOverviews) {
  constexpr int samples = 400, lines = 300, bands = 12;
  const auto value = [](int l, int b, int s) {
    return s < l / 4 ? std::nanf("") : 10.0f * b + 0.125f * s + 0.0625f * l;
  };
  TempFolder dir;
  EnviHeader header = orthoHeader(utmMapInfo(31, true), EnviInterleave::bil);
  header.samples = samples;
  header.lines = lines;
  header.bands = bands;
  header.wavelength.clear();
  for (int b = 0; b < bands; ++b) header.wavelength.push_back(400.0 + 10.0 * b);
  EnviWriter writer(dir / "ortho.hdr", header);
  std::vector<float> line(static_cast<std::size_t>(samples) * bands);
  for (int l = 0; l < lines; ++l) {
    for (int b = 0; b < bands; ++b) {
      for (int s = 0; s < samples; ++s) line[static_cast<std::size_t>(b) * samples + s] = value(l, b, s);
    }
    writer.writeLine(line.data());
  }
  writer.finish();
  GeoTiffExportOptions options;
  options.block_size = 64;  // overviews 200 x 150, 100 x 75, 50 x 38, several tiles each
  struct GlobalGdalSettings {
    CPLErrorHandler previous;
    GlobalGdalSettings() {
      worker_errors = 0;
      CPLSetConfigOption("GDAL_NUM_THREADS", "ALL_CPUS");
      previous = CPLSetErrorHandler(countErrors);
    }
    ~GlobalGdalSettings() {
      CPLSetErrorHandler(previous);
      CPLSetConfigOption("GDAL_NUM_THREADS", nullptr);
    }
  };
  {
    const GlobalGdalSettings settings;
    exportEnviToCog(dir / "ortho.hdr", dir / "ortho.tif", options);
  }
  EXPECT_EQ(worker_errors.load(), 0);

  const Dataset tif = openWithGdal(dir / "ortho.tif", "GTiff");
  ASSERT_NE(tif, nullptr);
  expectCloudOptimizedLayout(dir / "ortho.tif", *tif);
  for (int b : {0, bands - 1}) {
    GDALRasterBand* band = tif->GetRasterBand(b + 1);
    ASSERT_EQ(band->GetOverviewCount(), 3);
    GDALRasterBand* overview = band->GetOverview(0);
    ASSERT_EQ(overview->GetXSize(), samples / 2);
    // Overview pixel (60, 40): the mean of lines 80..81, samples 120..121.
    float mean = 0;
    ASSERT_EQ(overview->RasterIO(GF_Read, 60, 40, 1, 1, &mean, 1, 1, GDT_Float32, 0, 0), CE_None);
    EXPECT_NEAR(mean, 10.0f * b + 0.125f * 120.5f + 0.0625f * 80.5f, 1e-3) << "band " << b + 1;
    // Overview pixel (2, 50): lines 100..101, samples 4..5 all NaN (s < l / 4).
    ASSERT_EQ(overview->RasterIO(GF_Read, 2, 50, 1, 1, &mean, 1, 1, GDT_Float32, 0, 0), CE_None);
    EXPECT_TRUE(std::isnan(mean)) << "band " << b + 1 << ": " << mean;
  }
}

// South of the equator: EPSG:327zz; a BIL file; a reference pixel other than
// (1, 1) moves the corner by whole and half pixels.
TEST(GeoTiffExport, SouthernHemisphereBilAndReferencePixel) {
  TempFolder dir;
  EnviMapInfo map = utmMapInfo(23, false);
  map.reference_pixel_x = 1.5;
  map.reference_pixel_y = 3;
  const std::filesystem::path hdr = writeOrtho(dir, orthoHeader(map, EnviInterleave::bil));
  exportEnviToCog(hdr, dir / "ortho.tif");

  const Dataset tif = openWithGdal(dir / "ortho.tif", "GTiff");
  ASSERT_NE(tif, nullptr);
  expectPixels(*tif);
  expectGeoTransform(*tif, 431234.5 - 0.5 * 0.02, 7456789.75 + 2 * 0.02, 0.02);
  ASSERT_NE(tif->GetSpatialRef(), nullptr);
  EXPECT_STREQ(tif->GetSpatialRef()->GetAuthorityCode(nullptr), "32723");
  expectSameCrsAsEpsg(*tif, 32723);
}

// GDAL's ENVI driver reads a UTM map info without datum as NAD27 (below); the
// export follows DATASET.md (results are WGS-84) instead.
TEST(GeoTiffExport, UtmMapInfoWithoutDatumIsWgs84) {
  TempFolder dir;
  EnviMapInfo map = utmMapInfo(31, true);
  map.datum.clear();
  EnviHeader header = orthoHeader(map);
  header.other_fields.clear();  // no data ignore value: float data gets NaN
  header.wavelength_units.clear();
  exportEnviToCog(writeOrtho(dir, header), dir / "ortho.tif");

  const Dataset tif = openWithGdal(dir / "ortho.tif", "GTiff");
  ASSERT_NE(tif, nullptr);
  EXPECT_STREQ(tif->GetSpatialRef()->GetAuthorityCode(nullptr), "32631");
  int has_nodata = 0;
  EXPECT_TRUE(std::isnan(tif->GetRasterBand(1)->GetNoDataValue(&has_nodata)));
  EXPECT_TRUE(has_nodata);
  EXPECT_STREQ(tif->GetRasterBand(1)->GetDescription(), "450.2 nm");
}

TEST(GeoTiffExport, HeaderWithoutMapInfoIsAnInputErrorAndWritesNothing) {
  TempFolder dir;
  const std::filesystem::path hdr = writeOrtho(dir, orthoHeader(std::nullopt));
  testing::expectInputError(
      [&] { exportEnviToCog(hdr, dir / "ortho.tif"); }, hdr,
      "key map info: required to export a GeoTIFF: expected {UTM, 1, 1, easting, northing, "
      "px, px, zone, North|South, WGS-84, units=Meters}, found none");
  EXPECT_EQ(filesIn(dir), (std::set<std::string>{"ortho.hdr", "ortho.raw"}));
}

TEST(GeoTiffExport, LocalMapInfoIsAnInputError) {
  TempFolder dir;
  EnviMapInfo map;
  map.projection = "Arbitrary";
  map.easting = 1.5;
  map.northing = 2.5;
  map.pixel_size_x = map.pixel_size_y = 0.01;
  map.units = "Meters";
  const std::filesystem::path hdr = writeOrtho(dir, orthoHeader(map));
  testing::expectInputError(
      [&] { exportEnviToCog(hdr, dir / "ortho.tif"); }, hdr,
      "key map info: required to export a GeoTIFF: expected {UTM, 1, 1, easting, northing, "
      "px, px, zone, North|South, WGS-84, units=Meters}, found projection 'Arbitrary'");
  EXPECT_EQ(filesIn(dir), (std::set<std::string>{"ortho.hdr", "ortho.raw"}));
}

// GDAL's ENVI driver reads a data file cut short as zeros, silently; the
// export checks the size first (EnviReader) and keeps the older ortho.tif.
TEST(GeoTiffExport, TruncatedDataIsAnInputErrorAndKeepsTheOldFile) {
  TempFolder dir;
  const std::filesystem::path hdr = writeOrtho(dir, orthoHeader(utmMapInfo(31, true)));
  const std::filesystem::path old_tif = dir.write("ortho.tif", "older product");
  std::filesystem::resize_file(dir / "ortho.raw", sizeof(float) * kSamples * kLines);
  testing::expectInputError(
      [&] { exportEnviToCog(hdr, old_tif); }, dir / "ortho.raw",
      " truncated: expected at least 14400 bytes (header offset 0 + 40 samples x 30 lines x "
      "3 bands x 4 bytes), found 4800");
  EXPECT_EQ(TempFolder::read(old_tif), "older product");
  EXPECT_EQ(filesIn(dir), (std::set<std::string>{"ortho.hdr", "ortho.raw", "ortho.tif"}));
}

// GDAL itself fails (its temporary name is taken by a folder): the error names
// the file with GDAL's reason, the older ortho.tif stays.
TEST(GeoTiffExport, GdalFailureKeepsTheOldFile) {
  TempFolder dir;
  const std::filesystem::path hdr = writeOrtho(dir, orthoHeader(utmMapInfo(31, true)));
  const std::filesystem::path old_tif = dir.write("ortho.tif", "older product");
  std::filesystem::create_directories(dir / "ortho.tif.partial" / "occupied");
  try {
    exportEnviToCog(hdr, old_tif);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string prefix = "cannot write " + old_tif.string() + ": ";
    EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u) << e.what();
    EXPECT_GT(std::string(e.what()).size(), prefix.size()) << e.what();
  }
  EXPECT_EQ(TempFolder::read(old_tif), "older product");
  EXPECT_EQ(filesIn(dir),
            (std::set<std::string>{"ortho.hdr", "ortho.raw", "ortho.tif", "ortho.tif.partial"}));
}

TEST(GeoTiffExport, UnwritableTargetNamesTheFileWithGdalsReason) {
  TempFolder dir;
  const std::filesystem::path hdr = writeOrtho(dir, orthoHeader(utmMapInfo(31, true)));
  const std::filesystem::path tif = dir / "missing-folder" / "ortho.tif";
  try {
    exportEnviToCog(hdr, tif);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("cannot write " + tif.string() + ": ", 0), 0u) << message;
    EXPECT_GT(message.size(), ("cannot write " + tif.string() + ": ").size()) << message;
  }
  EXPECT_EQ(filesIn(dir), (std::set<std::string>{"ortho.hdr", "ortho.raw"}));
  // GDAL's handler was restored: its errors reach the default handler again.
  EXPECT_EQ(CPLGetErrorHandlerUserData(), nullptr);
}

TEST(GeoTiffExportOptions, ValidateNamesTheField) {
  GeoTiffExportOptions options;
  EXPECT_NO_THROW(options.validate());
  options.block_size = 100;
  EXPECT_THROW(options.validate(), std::invalid_argument);
  options = {};
  options.compression = "JPEG";
  try {
    options.validate();
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(
        e.what(),
        "GeoTiffExportOptions.compression must be one of DEFLATE, ZSTD, LZW, LZMA, NONE, got 'JPEG'");
  }
  options = {};
  options.overview_resampling = "average";
  EXPECT_THROW(options.validate(), std::invalid_argument);
  options = {};
  options.threads = -1;
  EXPECT_THROW(options.validate(), std::invalid_argument);
}

// The ENVI ortho itself must be readable by GIS tools through GDAL's ENVI
// driver (DATASET.md: "so that GIS tools place them on the map"): what GDAL
// 3.6 makes of a header written by hsmap's writer.
TEST(GdalReadsHsmapEnvi, MapInfoWavelengthsAndDataIgnoreValue) {
  TempFolder dir;
  for (const bool north : {true, false}) {
    writeOrtho(dir, orthoHeader(utmMapInfo(31, north), north ? EnviInterleave::bsq : EnviInterleave::bil));
    const Dataset envi = openWithGdal(dir / "ortho.raw", "ENVI");  // GDAL opens the data file
    ASSERT_NE(envi, nullptr);
    EXPECT_EQ(envi->GetRasterXSize(), kSamples);
    EXPECT_EQ(envi->GetRasterYSize(), kLines);
    expectPixels(*envi);
    expectGeoTransform(*envi, 431234.5, north ? 4761020.25 : 7456789.75, 0.02);
    // The CRS is right but carries no EPSG code (PROJCS "unnamed").
    expectSameCrsAsEpsg(*envi, north ? 32631 : 32731);
    EXPECT_EQ(envi->GetSpatialRef()->GetAuthorityCode(nullptr), nullptr);
    int has_nodata = 0;
    EXPECT_TRUE(std::isnan(envi->GetRasterBand(1)->GetNoDataValue(&has_nodata)));
    EXPECT_TRUE(has_nodata);
    EXPECT_STREQ(envi->GetRasterBand(1)->GetDescription(), "450.2 Nanometers");
    EXPECT_EQ(metadataItem(*envi->GetRasterBand(3), "wavelength"), "650.75");
  }
}

TEST(GdalReadsHsmapEnvi, TheHeaderIsNotOpenedOnlyTheDataFile) {
  TempFolder dir;
  writeOrtho(dir, orthoHeader(utmMapInfo(31, true)));
  CPLPushErrorHandler(CPLQuietErrorHandler);
  const Dataset envi = openWithGdal(dir / "ortho.hdr", "ENVI");
  CPLPopErrorHandler();
  EXPECT_EQ(envi, nullptr);
}

TEST(GdalReadsHsmapEnvi, UtmWithoutDatumIsReadAsNad27) {
  TempFolder dir;
  EnviMapInfo map = utmMapInfo(31, true);
  map.datum.clear();
  writeOrtho(dir, orthoHeader(map));
  const Dataset envi = openWithGdal(dir / "ortho.raw", "ENVI");
  ASSERT_NE(envi, nullptr);
  ASSERT_NE(envi->GetSpatialRef(), nullptr);
  EXPECT_STREQ(envi->GetSpatialRef()->GetAttrValue("GEOGCS"), "NAD27");
}

}  // namespace
}  // namespace hsmap
