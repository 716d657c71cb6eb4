// envi_stream_tool: measures streaming an ENVI cube with EnviReader, for
// benchmarks/envi_stream_benchmark.sh (which runs it under /usr/bin/time -v).
//
//   envi_stream_tool write HDR --samples 1920 --bands 211 --lines N --interleave bil --type 12
//       writes a cube through EnviWriter with deterministic content
//   envi_stream_tool read HDR [--mode buffered|mapped] [--full-checksum]
//       reads every line in order with EnviReader::readLine into one reused
//       buffer and prints lines, bytes, seconds, GB/s and a checksum
//
// The checksum adds three values of each line (all values with
// --full-checksum): readLine lives in another translation unit, so the
// conversion cannot be optimised away, and the light checksum keeps the
// measurement about reading rather than summing.

#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/io/envi_reader.h"
#include "core/io/envi_writer.h"

namespace {

// Deterministic, varied content within uint8 range after scaling, so that
// every data type can hold it.
float cubeValue(int line, int band, int sample) {
  return static_cast<float>((line * 131 + band * 31 + sample * 7) % 4093) / 16.0f;
}

int writeCube(const std::string& hdr, int samples, int bands, int lines, const std::string& interleave,
              int type) {
  hsmap::EnviHeader header;
  header.samples = samples;
  header.bands = bands;
  header.lines = lines;
  header.data_type = static_cast<hsmap::EnviDataType>(type);
  if (interleave == "bsq") {
    header.interleave = hsmap::EnviInterleave::bsq;
  } else if (interleave == "bip") {
    header.interleave = hsmap::EnviInterleave::bip;
  } else {
    header.interleave = hsmap::EnviInterleave::bil;
  }
  header.description = "envi_stream_tool benchmark cube";
  for (int b = 0; b < bands; ++b) header.wavelength.push_back(400.0 + 300.0 * b / bands);
  header.wavelength_units = "Nanometers";
  hsmap::EnviWriter writer(hdr, header);
  std::vector<float> line(static_cast<std::size_t>(samples) * bands);
  for (int l = 0; l < lines; ++l) {
    for (int b = 0; b < bands; ++b) {
      for (int s = 0; s < samples; ++s) line[static_cast<std::size_t>(b) * samples + s] = cubeValue(l, b, s);
    }
    writer.writeLine(line.data());
  }
  writer.finish();
  std::printf("wrote %s: %d samples x %d lines x %d bands, %s, %s, %.3f GB\n", hdr.c_str(), samples, lines,
              bands, hsmap::toString(header.interleave), hsmap::toString(header.data_type),
              static_cast<double>(header.dataBytes()) / 1e9);
  return 0;
}

int readCube(const std::string& hdr, const std::string& mode, bool full_checksum) {
  const auto start = std::chrono::steady_clock::now();
  const hsmap::EnviReader reader(hdr, mode == "mapped" ? hsmap::EnviReadMode::mapped : hsmap::EnviReadMode::buffered);
  const std::size_t values = static_cast<std::size_t>(reader.samples()) * reader.bands();
  std::vector<float> line(values);
  double checksum = 0;
  for (int l = 0; l < reader.lines(); ++l) {
    reader.readLine(l, line.data());
    if (full_checksum) {
      for (const float v : line) checksum += v;
    } else {
      checksum += line[0] + line[(static_cast<std::size_t>(l) * 7919) % values] + line[values - 1];
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double bytes = static_cast<double>(reader.header().dataBytes());
  std::printf("mode %s lines %d bytes %.0f seconds %.3f GB/s %.3f checksum %.6e\n", mode.c_str(), reader.lines(),
              bytes, seconds, bytes / seconds / 1e9, checksum);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Write or stream-read an ENVI cube (benchmark helper)"};
  app.require_subcommand(1);

  std::string write_hdr;
  int samples = 1920, bands = 211, lines = 100, type = 12;
  std::string interleave = "bil";
  CLI::App* write = app.add_subcommand("write", "write a deterministic cube through EnviWriter");
  write->add_option("hdr", write_hdr, "header path (data: same stem + .raw)")->required();
  write->add_option("--samples", samples, "samples per line")->check(CLI::PositiveNumber);
  write->add_option("--bands", bands, "bands")->check(CLI::PositiveNumber);
  write->add_option("--lines", lines, "lines")->check(CLI::PositiveNumber);
  write->add_option("--interleave", interleave, "bsq, bil or bip")->check(CLI::IsMember({"bsq", "bil", "bip"}));
  write->add_option("--type", type, "ENVI data type")->check(CLI::IsMember({1, 2, 3, 4, 5, 12, 13}));

  std::string read_hdr;
  bool full_checksum = false;
  std::string mode = "buffered";
  CLI::App* read = app.add_subcommand("read", "read every line in order with EnviReader");
  read->add_option("hdr", read_hdr, "header path")->required();
  read->add_option("--mode", mode, "buffered (pread, the default) or mapped (mmap)")
      ->check(CLI::IsMember({"buffered", "mapped"}));
  read->add_flag("--full-checksum", full_checksum, "sum every value instead of three per line");

  CLI11_PARSE(app, argc, argv);
  try {
    if (*write) return writeCube(write_hdr, samples, bands, lines, interleave, type);
    return readCube(read_hdr, mode, full_checksum);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
}
