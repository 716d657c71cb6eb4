#pragma once
// ENVI header (.hdr): the text file that describes a raw raster (the UHI cube,
// the hyperspectral ortho-image, truth/reflectance).
//
// Grammar (what readEnviHeader accepts)
//   line 1          `ENVI`
//   `key = value`   keys are case-insensitive and runs of blanks count as one
//                   blank (`Data  Type` is `data type`); a key appears once
//   `{ ... }`       a value in braces may span several lines (lists, text)
//   `; text`        a comment line
//   blank lines     ignored
// Required keys: samples, lines, bands, data type, interleave. Known optional
// keys: header offset, byte order, file type, wavelength, wavelength units,
// fwhm, band names, map info, description. Any other key is kept verbatim
// in `other_fields` (in file order) and written back unchanged.
//
// Checks (each failure is an InputError naming the header, the line of the
// offending key, or the key itself when it is missing, and what was expected):
// sizes are positive integers whose product in bytes, plus the header
// offset, fits in a file (checked without 64-bit wrap-around), data type is one of 1 2 3 4 5 12 13, byte
// order is 0 or 1, interleave is bsq/bil/bip, wavelength/fwhm/band names
// have one entry per band, numbers are finite (no nan/inf), fwhm values are
// > 0, map info has the fields below. Before parsing, the text goes through
// normaliseText() (core/util/text_file.h) with TextEncoding::any_bytes.
//
// Map info (DATASET.md, "Rasters with a map position"):
//   {projection, ref_x, ref_y, easting, northing, px_x, px_y[, zone, North|South][, datum][, units=U]}
// The reference pixel (ref_x, ref_y) is 1-based as ENVI writes it: (1, 1) is
// the upper-left corner of the upper-left pixel. UTM requires zone and
// hemisphere. Other `key=value` items (e.g. `rotation=`) are rejected rather
// than ignored: a rotated raster read as north-up would be silently wrong.
//
// writeEnviHeader writes a header (atomically: temp name + rename) that
// readEnviHeader reads back to an equal EnviHeader, laid out as GDAL's ENVI
// driver writes them.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hsmap {

enum class EnviInterleave { bsq, bil, bip };

// ENVI `data type` codes.
enum class EnviDataType : int {
  uint8 = 1,
  int16 = 2,
  int32 = 3,
  float32 = 4,
  float64 = 5,
  uint16 = 12,
  uint32 = 13
};

std::size_t bytesPerValue(EnviDataType type);
// "bsq", "bil", "bip"; "uint8", "int16", ...
const char* toString(EnviInterleave interleave);
const char* toString(EnviDataType type);

struct EnviMapInfo {
  std::string projection;  // "UTM", "Arbitrary", ...
  double reference_pixel_x = 1, reference_pixel_y = 1;  // 1-based, as ENVI writes
  double easting = 0, northing = 0, pixel_size_x = 0, pixel_size_y = 0;
  int zone = 0;
  bool north = true;
  std::string datum;  // "WGS-84"; empty when absent
  std::string units;  // "Meters"; empty when absent

  bool operator==(const EnviMapInfo&) const = default;
};

struct EnviHeader {
  int samples = 0, lines = 0, bands = 0;
  std::uint64_t header_offset = 0;
  EnviDataType data_type = EnviDataType::float32;
  EnviInterleave interleave = EnviInterleave::bil;
  int byte_order = 0;  // 0 little endian, 1 big endian
  std::string file_type = "ENVI Standard";
  std::vector<double> wavelength;  // empty or `bands` values
  std::string wavelength_units;    // e.g. "Nanometers"
  std::vector<double> fwhm;        // empty or `bands` values
  std::vector<std::string> band_names;  // empty or `bands` names
  std::optional<EnviMapInfo> map_info;
  std::string description;
  std::vector<std::string> comments;  // text of the lines starting with ';'
  std::vector<std::pair<std::string, std::string>> other_fields;  // unknown keys kept verbatim, in order

  // samples * lines * bands * bytesPerValue(data_type)
  std::uint64_t dataBytes() const;

  bool operator==(const EnviHeader&) const = default;
};

// Throws InputError (file + line or key + expectation). The file is read as
// a regular file of at most kMaxEnviHeaderBytes (core/util/text_file.h).
EnviHeader readEnviHeader(const std::filesystem::path& hdr_path);
// The same parser on the header's text `raw`; `hdr_path` names it in errors.
EnviHeader parseEnviHeader(std::string_view raw, const std::filesystem::path& hdr_path);

// The text of the header as writeEnviHeader writes it. std::invalid_argument
// for a header that could not be read back (sizes not positive, list sizes not
// matching `bands`, text that would break the grammar).
std::string formatEnviHeader(const EnviHeader& header);

// Atomic (temp name + rename). std::invalid_argument for a header that could
// not be read back (sizes not positive, list sizes not matching `bands`, text
// that would break the grammar); std::runtime_error when writing fails.
void writeEnviHeader(const std::filesystem::path& hdr_path, const EnviHeader& header);

// The data file of a header: cube.hdr -> the first existing of cube.raw,
// cube.img, cube.dat, cube.bsq, cube.bil, cube.bip, cube (the last also covers
// GDAL's `cube.raw.hdr` -> `cube.raw`). InputError naming the header and the
// names tried if none exists.
std::filesystem::path findEnviDataFile(const std::filesystem::path& hdr_path);

}  // namespace hsmap
