#include "core/io/envi_header.h"

#include <gtest/gtest.h>

#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

constexpr const char* kFullHeader =
    "ENVI\n"
    "description = {\n"
    "  Synthetic UHI cube,\n"
    "  for tests}\n"
    "samples = 3\n"
    "Lines   =  2\n"
    "BANDS = 4\n"
    "header offset = 16\n"
    "file type = ENVI Standard\n"
    "data  type = 12\n"
    "interleave = BIP\n"
    "byte order = 1\n"
    "; a comment line\n"
    "\n"
    "wavelength units = Nanometers\n"
    "wavelength = {400.5, 450,\n"
    "  500.25,\n"
    "  550}\n"
    "fwhm = { 5, 5.5, 6, 6.5 }\n"
    "band names = {b1, b2,\n"
    " b3, b4}\n"
    "map info = {UTM, 1, 1, 500000.5, 4760000, 0.25, 0.25, 31, North, WGS-84, units=Meters}\n"
    "sensor type = Unknown\n"
    "default bands = {3,\n"
    "  2, 1}\n";

TEST(EnviHeader, ParsesEveryKnownFieldAndKeepsUnknownOnes) {
  TempFolder dir;
  const EnviHeader header = readEnviHeader(dir.write("cube.hdr", kFullHeader));
  EXPECT_EQ(header.samples, 3);
  EXPECT_EQ(header.lines, 2);
  EXPECT_EQ(header.bands, 4);
  EXPECT_EQ(header.header_offset, 16u);
  EXPECT_EQ(header.file_type, "ENVI Standard");
  EXPECT_EQ(header.data_type, EnviDataType::uint16);
  EXPECT_EQ(header.interleave, EnviInterleave::bip);
  EXPECT_EQ(header.byte_order, 1);
  EXPECT_EQ(header.description, "Synthetic UHI cube,\n  for tests");
  EXPECT_EQ(header.wavelength_units, "Nanometers");
  EXPECT_EQ(header.wavelength, (std::vector<double>{400.5, 450, 500.25, 550}));
  EXPECT_EQ(header.fwhm, (std::vector<double>{5, 5.5, 6, 6.5}));
  EXPECT_EQ(header.band_names, (std::vector<std::string>{"b1", "b2", "b3", "b4"}));
  ASSERT_TRUE(header.map_info.has_value());
  EXPECT_EQ(header.map_info->projection, "UTM");
  EXPECT_EQ(header.map_info->reference_pixel_x, 1.0);
  EXPECT_EQ(header.map_info->reference_pixel_y, 1.0);
  EXPECT_EQ(header.map_info->easting, 500000.5);
  EXPECT_EQ(header.map_info->northing, 4760000.0);
  EXPECT_EQ(header.map_info->pixel_size_x, 0.25);
  EXPECT_EQ(header.map_info->pixel_size_y, 0.25);
  EXPECT_EQ(header.map_info->zone, 31);
  EXPECT_TRUE(header.map_info->north);
  EXPECT_EQ(header.map_info->datum, "WGS-84");
  EXPECT_EQ(header.map_info->units, "Meters");
  EXPECT_EQ(header.comments, (std::vector<std::string>{"a comment line"}));
  const std::vector<std::pair<std::string, std::string>> other{
      {"sensor type", "Unknown"}, {"default bands", "{3,\n  2, 1}"}};
  EXPECT_EQ(header.other_fields, other);
  EXPECT_EQ(header.dataBytes(), 3u * 2u * 4u * 2u);
}

TEST(EnviHeader, WriteThenReadGivesTheSameHeader) {
  TempFolder dir;
  const EnviHeader original = readEnviHeader(dir.write("in.hdr", kFullHeader));
  writeEnviHeader(dir / "out.hdr", original);
  EXPECT_EQ(readEnviHeader(dir / "out.hdr"), original);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.hdr.partial"));

  // The local-frame form of DATASET.md, a South UTM zone and defaults.
  EnviHeader local;
  local.samples = 1920;
  local.lines = 7;
  local.bands = 2;
  local.data_type = EnviDataType::float32;
  local.interleave = EnviInterleave::bsq;
  local.wavelength = {400.123456789012, 1e-3};
  local.map_info = EnviMapInfo{"Arbitrary", 1, 1, -12.5, 0.1 + 0.2, 0.01, 0.01, 0, true, "", "Meters"};
  writeEnviHeader(dir / "local.hdr", local);
  EXPECT_EQ(readEnviHeader(dir / "local.hdr"), local);
  EXPECT_NE(TempFolder::read(dir / "local.hdr").find("map info = {Arbitrary, 1, 1, -12.5, 0.30000000000000004, "
                                                     "0.01, 0.01, units=Meters}"),
            std::string::npos);

  local.map_info = EnviMapInfo{"UTM", 1.5, 2.5, 300000, 7000000, 1, 2, 23, false, "WGS-84", "Meters"};
  writeEnviHeader(dir / "south.hdr", local);
  EXPECT_EQ(readEnviHeader(dir / "south.hdr"), local);
}

TEST(EnviHeader, WriterRejectsHeadersThatWouldNotReadBack) {
  TempFolder dir;
  EnviHeader header;
  header.samples = 2;
  header.lines = 2;
  header.bands = 3;
  header.wavelength = {1, 2};
  EXPECT_THROW(writeEnviHeader(dir / "a.hdr", header), std::invalid_argument);
  header.wavelength.clear();
  header.description = "has a } brace";
  EXPECT_THROW(writeEnviHeader(dir / "a.hdr", header), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "a.hdr"));
}

TEST(EnviHeader, FindsTheDataFileNextToTheHeader) {
  TempFolder dir;
  const auto hdr = dir.write("cube.hdr", kFullHeader);
  try {
    findEnviDataFile(hdr);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              hdr.string() + ": no data file found next to the header (tried cube.raw, cube.img, "
                             "cube.dat, cube.bsq, cube.bil, cube.bip, cube)");
  }
  dir.write("cube.img", "x");
  EXPECT_EQ(findEnviDataFile(hdr), dir / "cube.img");
  dir.write("cube.raw", "x");
  EXPECT_EQ(findEnviDataFile(hdr), dir / "cube.raw");
  // GDAL's naming: data.bin with data.bin.hdr.
  const auto gdal_hdr = dir.write("data.bin.hdr", kFullHeader);
  dir.write("data.bin", "x");
  EXPECT_EQ(findEnviDataFile(gdal_hdr), dir / "data.bin");
}

// A header that is valid except for the lines given in `body`.
struct BadHeaderCase {
  const char* name;
  std::string text;
  std::string expected;  // what() after "<path>:"
};

class EnviHeaderErrors : public ::testing::TestWithParam<BadHeaderCase> {};

TEST_P(EnviHeaderErrors, NameTheFileTheLineOrKeyAndTheExpectation) {
  TempFolder dir;
  const auto path = dir.write("bad.hdr", GetParam().text);
  try {
    readEnviHeader(path);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), path.string() + ":" + GetParam().expected);
    EXPECT_EQ(error.file(), path);
  }
}

std::string valid(const std::string& extra) {
  return "ENVI\nsamples = 3\nlines = 2\nbands = 2\ndata type = 4\ninterleave = bil\n" + extra;
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, EnviHeaderErrors,
    ::testing::Values(
        BadHeaderCase{"NoMagic", "ENVY\nsamples = 3\n", "line 1: expected 'ENVI' on line 1, found 'ENVY'"},
        BadHeaderCase{"EmptyFile", "", "line 1: expected 'ENVI' on line 1, found ''"},
        BadHeaderCase{"MissingSamples", "ENVI\nlines = 2\nbands = 2\ndata type = 4\ninterleave = bil\n",
                      "key samples: required key is missing"},
        BadHeaderCase{"MissingInterleave", "ENVI\nsamples = 3\nlines = 2\nbands = 2\ndata type = 4\n",
                      "key interleave: required key is missing"},
        BadHeaderCase{"MissingDataType", "ENVI\nsamples = 3\nlines = 2\nbands = 2\ninterleave = bil\n",
                      "key data type: required key is missing"},
        BadHeaderCase{"SamplesNotANumber", "ENVI\nsamples = three\nlines = 2\nbands = 2\ndata type = 4\ninterleave = bil\n",
                      "line 2: key 'samples': expected a positive integer, found 'three'"},
        BadHeaderCase{"ZeroBands", "ENVI\nsamples = 3\nlines = 2\nbands = 0\ndata type = 4\ninterleave = bil\n",
                      "line 4: key 'bands': expected a positive integer, found '0'"},
        BadHeaderCase{"BadDataType", "ENVI\nsamples = 3\nlines = 2\nbands = 2\nData Type = 6\ninterleave = bil\n",
                      "line 5: key 'data type': expected one of 1, 2, 3, 4, 5, 12, 13 (uint8, int16, int32, "
                      "float32, float64, uint16, uint32), found '6'"},
        BadHeaderCase{"BadInterleave", "ENVI\nsamples = 3\nlines = 2\nbands = 2\ndata type = 4\ninterleave = bsx\n",
                      "line 6: key 'interleave': expected bsq, bil or bip, found 'bsx'"},
        BadHeaderCase{"BadByteOrder", valid("byte order = 2\n"),
                      "line 7: key 'byte order': expected 0 (little endian) or 1 (big endian), found '2'"},
        BadHeaderCase{"NegativeOffset", valid("header offset = -4\n"),
                      "line 7: key 'header offset': expected a non-negative integer, found '-4'"},
        BadHeaderCase{"WavelengthCount", valid("wavelength = {400,\n 500, 600}\n"),
                      "line 7: key 'wavelength': expected 2 values (one per band), found 3"},
        BadHeaderCase{"FwhmCount", valid("fwhm = {5}\n"),
                      "line 7: key 'fwhm': expected 2 values (one per band), found 1"},
        BadHeaderCase{"WavelengthNotANumber", valid("wavelength = {400, 5OO}\n"),
                      "line 7: key 'wavelength': expected a finite number as item 2, found '5OO'"},
        BadHeaderCase{"FwhmNan", valid("fwhm = {nan, 5}\n"),
                      "line 7: key 'fwhm': expected a finite number as item 1, found 'nan'"},
        BadHeaderCase{"FwhmMinusInf", valid("fwhm = {5, -inf}\n"),
                      "line 7: key 'fwhm': expected a finite number as item 2, found '-inf'"},
        BadHeaderCase{"FwhmNotPositive", valid("fwhm = {5, 0}\n"),
                      "line 7: key 'fwhm': expected band widths > 0, found 0 for band 2"},
        BadHeaderCase{"HeaderOffsetWrapsAround", valid("header offset = 18446744073709551600\n"),
                      "line 7: key 'header offset': 18446744073709551600 bytes before 48 bytes of "
                      "data is beyond the largest possible file (2^63 bytes); expected the number "
                      "of bytes that precede the data in the data file"},
        BadHeaderCase{"SizeProductOverflows",
                      "ENVI\nsamples = 2147483647\nlines = 2147483647\nbands = 2147483647\n"
                      "data type = 5\ninterleave = bil\n",
                      "line 4: key 'bands': samples 2147483647 x lines 2147483647 x bands "
                      "2147483647 x 8 bytes per value is larger than any file can be (2^63 bytes); "
                      "expected the sizes of a real raster"},
        BadHeaderCase{"BinaryValueEscaped", valid("interleave2 = x\n") + "data type = \xFF\xFE\n",
                      "line 8: key 'data type' appears twice (first on line 5)"},
        BadHeaderCase{"NulByte", valid(std::string("description = {a\0b}\n", 20)),
                      "line 7: control character 0x00 (NUL) in column 17; expected text (is this a "
                      "binary or damaged file?)"},
        BadHeaderCase{"WavelengthNotAList", valid("wavelength = 400\n"),
                      "line 7: key 'wavelength': expected a list in braces '{ ... }', found '400'"},
        BadHeaderCase{"UnclosedBrace", valid("description = {never\nclosed\n"),
                      "line 7: key 'description': '{' opened on this line is never closed by '}'"},
        BadHeaderCase{"TextAfterBrace", valid("wavelength = {1,\n2} 3\n"),
                      "line 8: key 'wavelength': unexpected text after '}': '3'"},
        BadHeaderCase{"NoEquals", valid("this line has no equals sign\n"),
                      "line 7: expected 'key = value' or a ';' comment, found 'this line has no equals sign'"},
        BadHeaderCase{"NoKey", valid(" = 5\n"), "line 7: expected a key before '='"},
        BadHeaderCase{"DuplicateKey", valid("SAMPLES = 4\n"), "line 7: key 'samples' appears twice (first on line 2)"},
        BadHeaderCase{"MapInfoTooShort", valid("map info = {UTM, 1, 1, 500000, 4000000, 0.5}\n"),
                      "line 7: key 'map info': expected {projection, reference pixel x, reference pixel y, "
                      "easting, northing, pixel size x, pixel size y[, zone, North|South][, datum][, units=...]}, "
                      "found 6 items"},
        BadHeaderCase{"MapInfoBadNumber", valid("map info = {UTM, 1, 1, east, 4000000, 0.5, 0.5, 31, North}\n"),
                      "line 7: key 'map info': expected a finite number for easting (item 4), found 'east'"},
        BadHeaderCase{"MapInfoUtmWithoutZone", valid("map info = {UTM, 1, 1, 5, 4, 0.5, 0.5, units=Meters}\n"),
                      "line 7: key 'map info': UTM map info needs a zone and North|South after the pixel size"},
        BadHeaderCase{"MapInfoBadZone", valid("map info = {UTM, 1, 1, 5, 4, 0.5, 0.5, 61, North, WGS-84}\n"),
                      "line 7: key 'map info': expected a UTM zone 1..60, found '61'"},
        BadHeaderCase{"MapInfoBadHemisphere", valid("map info = {UTM, 1, 1, 5, 4, 0.5, 0.5, 31, Up, WGS-84}\n"),
                      "line 7: key 'map info': expected North or South, found 'Up'"},
        BadHeaderCase{"MapInfoRotation",
                      valid("map info = {UTM, 1, 1, 5, 4, 0.5, 0.5, 31, North, WGS-84, rotation=30}\n"),
                      "line 7: key 'map info': unsupported map info item 'rotation=30' (only units=... is "
                      "understood; rotated rasters are not supported)"}),
    [](const ::testing::TestParamInfo<BadHeaderCase>& info) { return std::string(info.param.name); });

TEST(EnviHeader, MissingFileIsAnInputError) {
  TempFolder dir;
  try {
    readEnviHeader(dir / "absent.hdr");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), (dir / "absent.hdr").string() + ": file not found");
  }
}

TEST(EnviHeader, BytesPerValueOfEveryType) {
  EXPECT_EQ(bytesPerValue(EnviDataType::uint8), 1u);
  EXPECT_EQ(bytesPerValue(EnviDataType::int16), 2u);
  EXPECT_EQ(bytesPerValue(EnviDataType::uint16), 2u);
  EXPECT_EQ(bytesPerValue(EnviDataType::int32), 4u);
  EXPECT_EQ(bytesPerValue(EnviDataType::uint32), 4u);
  EXPECT_EQ(bytesPerValue(EnviDataType::float32), 4u);
  EXPECT_EQ(bytesPerValue(EnviDataType::float64), 8u);
}

}  // namespace
}  // namespace hsmap
