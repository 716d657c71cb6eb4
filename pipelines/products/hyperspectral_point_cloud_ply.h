#pragma once
// RUN/hyperspectral/points.ply: the hyperspectral point cloud's file, a
// binary little-endian PLY that numpy, plyfile, Open3D, CloudCompare and
// hsmap's readPly read:
//
//   ply
//   format binary_little_endian 1.0
//   comment hsmap hyperspectral point cloud: UHI hits binned into cubes of <c> m, mean position and mean spectrum
//   comment frame W: local north-east-down in metres (x north, y east, z down) at lat <deg> lon <deg> depth <m>
//   comment band b000 wavelength_nm 400.5          one line per band, in band order
//   ...
//   element vertex 000000123456                     zero-padded (patched when the file is complete)
//   property double x                               mean hit position in W
//   property double y
//   property double z
//   property uint hits                              hits averaged into the point
//   property float b000                             mean value of band 0, in the cube's units
//   ...
//   end_header
//
// then one packed record per point (24 + 4 + 4 * bands bytes, no padding).
// The writer streams: points go out as they come, the count is written over
// its placeholder at the end, and the file is written as
// `points.ply.partial` and renamed when complete (AtomicFile).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/geometry/geodetic_point.h"
#include "core/io/atomic_file.h"
#include "pipelines/products/spectral_cell_binner.h"

namespace hsmap {

class HyperspectralPointCloudWriter {
 public:
  // Opens `<path>.partial` and writes the header. std::invalid_argument for
  // no wavelengths; std::runtime_error when the file cannot be created.
  HyperspectralPointCloudWriter(const std::filesystem::path& path, const std::vector<double>& wavelengths_nm,
                                double cell_m, const GeodeticPoint& origin);

  // Appends a point (its spectrum has one float per wavelength).
  void write(const CellPoint& point);
  // Writes the count and moves the file into place; std::runtime_error on a
  // failed write. Without commit() nothing appears under the final name.
  void commit();

  std::int64_t points() const { return points_; }
  std::int64_t bytes() const;  // of the file so far (all of it after commit)

 private:
  void flushBuffer();

  AtomicFile file_;
  int bands_;
  std::streamoff count_offset_ = 0;
  std::int64_t header_bytes_ = 0, points_ = 0;
  std::vector<char> buffer_;
};

// A whole points.ply in memory (tests, small clouds; a script reads it as in
// docs/PRODUCTS.md). InputError naming the file for anything not written as above.
struct HyperspectralPointCloud {
  std::vector<double> wavelengths_nm;  // from the band comments
  double cell_m = 0.0;                 // from the first comment
  std::vector<Eigen::Vector3d> p_W;
  std::vector<std::uint32_t> hits;
  std::vector<float> spectra;  // point-major: spectra[point * bands + band]
  int bands() const { return int(wavelengths_nm.size()); }
};

HyperspectralPointCloud readHyperspectralPointCloud(const std::filesystem::path& path);

}  // namespace hsmap
