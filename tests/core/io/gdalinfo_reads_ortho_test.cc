// What GDAL's own command-line reader, `gdalinfo -json`, makes of the files a
// user gets from the hyperspectral stage: the ENVI ortho-image (ortho.raw with
// ortho.hdr beside it) and its GeoTIFF (exportEnviToCog). The ortho is
// written as hsmap writes it: ENVI float32 BIL, `map info` in UTM on WGS-84,
// wavelengths in nm, NaN where nothing was seen and `data ignore value = NaN`.
//
// gdalinfo comes with Debian's gdal-bin, which scripts/setup.sh installs; its
// absence is a failure, not a skip.

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <cpl_json.h>

#include <gtest/gtest.h>

#include "core/io/envi_header.h"
#include "core/io/envi_ignore_value.h"
#include "core/io/envi_writer.h"
#include "core/io/geotiff_export.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

constexpr int kSamples = 70, kLines = 45;
const std::vector<double> kWavelengths = {401.5, 480.25, 550, 620.125, 700.75};
const int kBands = static_cast<int>(kWavelengths.size());
constexpr double kEasting = 512345.5, kPixel = 0.05;

// Empty (NaN) left of a slanted swath edge and in the last lines, as at the
// ends of a survey; smooth spectra inside.
float orthoValue(int l, int b, int s) {
  if (s < l / 3 || l >= kLines - 4) return std::nanf("");
  const float db = static_cast<float>(b), ds = static_cast<float>(s), dl = static_cast<float>(l);
  return 100.0f + 2.0f * db + 0.5f * ds + 0.25f * dl;
}

double northingFor(bool north) { return north ? 4761020.25 : 7456789.75; }

std::filesystem::path writeOrtho(const TempFolder& dir, int zone, bool north) {
  EnviHeader header;
  header.samples = kSamples;
  header.lines = kLines;
  header.bands = kBands;
  header.data_type = EnviDataType::float32;
  header.interleave = EnviInterleave::bil;
  header.wavelength_units = "Nanometers";
  header.wavelength = kWavelengths;
  EnviMapInfo map;
  map.projection = "UTM";
  map.easting = kEasting;
  map.northing = northingFor(north);
  map.pixel_size_x = map.pixel_size_y = kPixel;
  map.zone = zone;
  map.north = north;
  map.datum = "WGS-84";
  map.units = "Meters";
  header.map_info = map;
  header.description = "hsmap products: hyperspectral ortho-image, NaN where nothing was seen";
  setDataIgnoreValueNaN(header);
  EnviWriter writer(dir / "ortho.hdr", header);
  std::vector<float> line(static_cast<std::size_t>(kSamples) * kBands);
  for (int l = 0; l < kLines; ++l) {
    for (int b = 0; b < kBands; ++b) {
      float* band_row = line.data() + static_cast<std::size_t>(b) * kSamples;
      for (int s = 0; s < kSamples; ++s) band_row[s] = orthoValue(l, b, s);
    }
    writer.writeLine(line.data());
  }
  writer.finish();
  return dir / "ortho.hdr";
}

// gdalinfo on the PATH, if any.
std::optional<std::filesystem::path> findGdalinfo() {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path != nullptr ? path : "/usr/bin:/bin");
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    const std::filesystem::path candidate = std::filesystem::path(folder.empty() ? "." : folder) / "gdalinfo";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

// `gdalinfo -json file`, parsed; a test failure (and an empty document) when
// gdalinfo is missing, fails or prints something that is not JSON.
CPLJSONObject gdalinfoJson(const TempFolder& dir, const std::filesystem::path& file) {
  const std::optional<std::filesystem::path> gdalinfo = findGdalinfo();
  if (!gdalinfo) {
    ADD_FAILURE() << "gdalinfo is not on the PATH: run scripts/setup.sh (it installs gdal-bin, GDAL's "
                     "command-line tools)";
    return {};
  }
  const std::filesystem::path errors = dir / "gdalinfo.stderr";
  const std::string command =
      "'" + gdalinfo->string() + "' -json '" + file.string() + "' 2> '" + errors.string() + "'";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "cannot run " << command;
    return {};
  }
  std::string output;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
  const int status = ::pclose(pipe);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    ADD_FAILURE() << command << " failed (status " << status << "): " << TempFolder::read(errors);
    return {};
  }
  CPLJSONDocument document;
  if (!document.LoadMemory(output)) {
    ADD_FAILURE() << command << " printed no JSON:\n" << output.substr(0, 2000);
    return {};
  }
  return document.GetRoot();
}

// The member `name` of `object` (by iteration: names such as "" and
// "proj:epsg" are not paths).
CPLJSONObject member(const CPLJSONObject& object, const std::string& name) {
  for (const CPLJSONObject& child : object.GetChildren()) {
    if (child.GetName() == name) return child;
  }
  return {};
}

std::vector<double> numbers(const CPLJSONObject& object, const std::string& name) {
  std::vector<double> out;
  const CPLJSONArray array = object.GetArray(name);
  for (int i = 0; array.IsValid() && i < array.Size(); ++i) out.push_back(array[i].ToDouble());
  return out;
}

// Size, bands with their wavelengths, geotransform: the same in both files.
void expectOrthoGrid(const CPLJSONObject& info, bool north, const std::string& description_units) {
  EXPECT_EQ(numbers(info, "size"), (std::vector<double>{kSamples, kLines}));
  const CPLJSONArray bands = info.GetArray("bands");
  ASSERT_TRUE(bands.IsValid());
  ASSERT_EQ(bands.Size(), kBands);
  for (int b = 0; b < kBands; ++b) {
    const CPLJSONObject band = bands[b];
    const CPLJSONObject items = member(band.GetObj("metadata"), "");
    const std::string wavelength = items.GetString("wavelength");
    ASSERT_FALSE(wavelength.empty()) << "band " << b + 1 << ": no wavelength";
    EXPECT_DOUBLE_EQ(std::stod(wavelength), kWavelengths[b]) << "band " << b + 1;
    EXPECT_EQ(items.GetString("wavelength_units"), "Nanometers") << "band " << b + 1;
    EXPECT_EQ(band.GetString("description"), wavelength + " " + description_units) << "band " << b + 1;
    EXPECT_EQ(band.GetString("type"), "Float32");
  }
  // {x0, px, 0, y0, 0, -py}: the upper-left corner of the upper-left pixel.
  const std::vector<double> gt = numbers(info, "geoTransform");
  ASSERT_EQ(gt.size(), 6u);
  EXPECT_DOUBLE_EQ(gt[0], kEasting);
  EXPECT_DOUBLE_EQ(gt[1], kPixel);
  EXPECT_EQ(gt[2], 0.0);
  EXPECT_DOUBLE_EQ(gt[3], northingFor(north));
  EXPECT_EQ(gt[4], 0.0);
  EXPECT_DOUBLE_EQ(gt[5], -kPixel);
}

class GdalinfoReadsOrtho : public ::testing::TestWithParam<bool> {};

TEST_P(GdalinfoReadsOrtho, EnviDataFileAndGeoTiff) {
  const bool north = GetParam();
  const int zone = north ? 31 : 33;
  const std::string zone_name = "UTM zone " + std::to_string(zone) + (north ? "N" : "S");
  TempFolder dir;
  const std::filesystem::path hdr = writeOrtho(dir, zone, north);
  GeoTiffExportOptions options;
  options.block_size = 32;  // overviews for a small image: 70 x 45 -> 35 x 23 -> 18 x 12
  exportEnviToCog(hdr, dir / "ortho.tif", options);

  {
    SCOPED_TRACE("ortho.raw");
    const CPLJSONObject envi = gdalinfoJson(dir, dir / "ortho.raw");
    ASSERT_TRUE(envi.IsValid());
    EXPECT_EQ(envi.GetString("driverShortName"), "ENVI");
    expectOrthoGrid(envi, north, "Nanometers");
    // GDAL's ENVI driver names no EPSG code ("unnamed" projected CRS), but
    // the UTM zone, hemisphere and datum are right.
    const std::string wkt = envi.GetObj("coordinateSystem").GetString("wkt");
    EXPECT_NE(wkt.find("CONVERSION[\"" + zone_name + "\""), std::string::npos) << wkt;
    EXPECT_NE(wkt.find("BASEGEOGCRS[\"WGS 84\""), std::string::npos) << wkt;
    EXPECT_NE(wkt.find("DATUM[\"World Geodetic System 1984\""), std::string::npos) << wkt;
    const CPLJSONArray bands = envi.GetArray("bands");
    ASSERT_EQ(bands.Size(), kBands);
    for (int b = 0; b < kBands; ++b) EXPECT_EQ(bands[b].GetString("noDataValue"), "NaN") << "band " << b + 1;
  }
  {
    SCOPED_TRACE("ortho.tif");
    const CPLJSONObject tif = gdalinfoJson(dir, dir / "ortho.tif");
    ASSERT_TRUE(tif.IsValid());
    EXPECT_EQ(tif.GetString("driverShortName"), "GTiff");
    expectOrthoGrid(tif, north, "nm");
    const int epsg = (north ? 32600 : 32700) + zone;
    const std::string wkt = tif.GetObj("coordinateSystem").GetString("wkt");
    EXPECT_NE(wkt.find("PROJCRS[\"WGS 84 / " + zone_name + "\""), std::string::npos) << wkt;
    EXPECT_NE(wkt.find("ID[\"EPSG\"," + std::to_string(epsg) + "]]"), std::string::npos) << wkt;
    EXPECT_EQ(member(tif.GetObj("stac"), "proj:epsg").ToInteger(), epsg);
    const CPLJSONArray bands = tif.GetArray("bands");
    ASSERT_EQ(bands.Size(), kBands);
    for (int b = 0; b < kBands; ++b) {
      EXPECT_EQ(bands[b].GetString("noDataValue"), "NaN") << "band " << b + 1;
      EXPECT_EQ(numbers(bands[b], "block"), (std::vector<double>{32, 32})) << "band " << b + 1;
      const CPLJSONArray overviews = bands[b].GetArray("overviews");
      ASSERT_TRUE(overviews.IsValid()) << "band " << b + 1 << ": no overviews";
      ASSERT_EQ(overviews.Size(), 2) << "band " << b + 1;
      EXPECT_EQ(numbers(overviews[0], "size"), (std::vector<double>{35, 23})) << "band " << b + 1;
      EXPECT_EQ(numbers(overviews[1], "size"), (std::vector<double>{18, 12})) << "band " << b + 1;
    }
    const CPLJSONObject structure = member(tif.GetObj("metadata"), "IMAGE_STRUCTURE");
    EXPECT_EQ(structure.GetString("COMPRESSION"), "DEFLATE");
    EXPECT_EQ(structure.GetString("INTERLEAVE"), "BAND");
  }
}

INSTANTIATE_TEST_SUITE_P(Hemispheres, GdalinfoReadsOrtho, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "North" : "South";
                         });

}  // namespace
}  // namespace hsmap
