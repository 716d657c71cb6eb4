#pragma once
// A float32 BIL copy of a survey's cube with some of its pixels spoiled
// (NaN, the data ignore value), for the tests of how the products and the
// tie points treat unusable pixels.
#include <Eigen/Core>
#include <filesystem>
#include <functional>
#include <sstream>

#include "core/io/envi_reader.h"
#include "core/io/envi_writer.h"

namespace hsmap::testing {

// Writes FOLDER/cube.hdr (and .raw): `cube` as little-endian float32 BIL
// whose header states `data ignore value = ignore_value`, each line
// (bands x samples) passed through spoil(line index, line) before it is
// written. Returns the header's path.
inline std::filesystem::path spoiledFloatCube(const EnviReader& cube, const std::filesystem::path& folder,
                                              float ignore_value,
                                              const std::function<void(int, Eigen::MatrixXf&)>& spoil) {
  EnviHeader header = cube.header();
  header.data_type = EnviDataType::float32;
  header.interleave = EnviInterleave::bil;
  header.byte_order = 0;
  header.header_offset = 0;
  std::ostringstream value;
  value << ignore_value;
  header.other_fields.emplace_back("data ignore value", value.str());
  const std::filesystem::path hdr = folder / "cube.hdr";
  EnviWriter writer(hdr, header);
  Eigen::MatrixXf line;
  for (int l = 0; l < cube.lines(); ++l) {
    cube.readLine(l, line);
    spoil(l, line);
    writer.writeLine(line);
  }
  writer.finish();
  return hdr;
}

}  // namespace hsmap::testing
