// geotiff_export_tool: measures exportEnviToCog on a hyperspectral ortho-image
// the size of a survey's, for benchmarks/geotiff_export_benchmark.sh (which
// runs it under /usr/bin/time -v, next to `gdal_translate -of COG`).
//
//   geotiff_export_tool write HDR [--samples 600 --lines 4000 --bands 211]
//       writes an ortho-image as hsmap's hyperspectral stage does: ENVI
//       float32 BIL, UTM 32N map info on WGS-84, wavelengths and fwhm in nm,
//       NaN outside a wandering swath
//   geotiff_export_tool export HDR TIF [--compression DEFLATE] [--no-overviews]
//       [--no-predictor] [--threads 0] [--block-size 512]
//       exportEnviToCog with those options; prints the seconds it took
//
// The spectra are smooth (a mix of three reflectance-like curves whose weights
// vary slowly across the image) plus a little deterministic noise, so codecs
// and predictors see what they would on a real ortho rather than random bits
// or constant planes.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/io/envi_writer.h"
#include "core/io/geotiff_export.h"

namespace {

// A reproducible value in [-1, 1) for (line, band, sample): sensor-like noise.
float noise(int line, int band, int sample) {
  std::uint32_t h = static_cast<std::uint32_t>(line) * 73856093u;
  h ^= static_cast<std::uint32_t>(band) * 19349663u;
  h ^= static_cast<std::uint32_t>(sample) * 83492791u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return static_cast<float>(h & 0xffffu) / 32768.0f - 1.0f;
}

int writeOrtho(const std::string& hdr, int samples, int lines, int bands) {
  hsmap::EnviHeader header;
  header.samples = samples;
  header.lines = lines;
  header.bands = bands;
  header.data_type = hsmap::EnviDataType::float32;
  header.interleave = hsmap::EnviInterleave::bil;
  header.wavelength_units = "Nanometers";
  for (int b = 0; b < bands; ++b) {
    header.wavelength.push_back(380.0 + 620.0 * b / std::max(bands - 1, 1));
    header.fwhm.push_back(3.5);
  }
  hsmap::EnviMapInfo map;
  map.projection = "UTM";
  map.easting = 500012.25;
  map.northing = 7034567.5;
  map.pixel_size_x = map.pixel_size_y = 0.01;
  map.zone = 32;
  map.north = true;
  map.datum = "WGS-84";
  map.units = "Meters";
  header.map_info = map;
  header.description = "geotiff_export_tool synthetic hyperspectral ortho-image, NaN where empty";

  // Three end-member spectra over the bands: sediment (rising), algae
  // (chlorophyll dip near 675 nm), rock (flat, dark).
  std::vector<float> sediment(bands), algae(bands), rock(bands);
  for (int b = 0; b < bands; ++b) {
    const double nm = header.wavelength[b];
    sediment[b] = static_cast<float>(0.05 + 0.25 * (nm - 380.0) / 620.0);
    algae[b] = static_cast<float>(0.08 + 0.06 * std::exp(-std::pow((nm - 550.0) / 40.0, 2)) -
                                  0.05 * std::exp(-std::pow((nm - 675.0) / 20.0, 2)) +
                                  0.3 / (1.0 + std::exp(-(nm - 720.0) / 15.0)));
    rock[b] = static_cast<float>(0.04 + 0.01 * std::sin(nm / 90.0));
  }
  hsmap::EnviWriter writer(hdr, header);
  std::vector<float> line(static_cast<std::size_t>(samples) * bands);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int l = 0; l < lines; ++l) {
    // The swath wanders like a vehicle's track; outside it the ortho is empty.
    const double centre = samples * (0.5 + 0.2 * std::sin(l / 700.0));
    const double half_width = samples * (0.3 + 0.05 * std::cos(l / 300.0));
    for (int s = 0; s < samples; ++s) {
      const bool empty = std::abs(s - centre) > half_width;
      const double u = std::sin(s / 57.0 + l / 211.0), v = std::cos(l / 131.0 - s / 97.0);
      const float w_sediment = static_cast<float>(0.5 + 0.4 * u);
      const float w_algae = static_cast<float>(0.3 + 0.25 * v);
      const float w_rock = 1.0f - 0.5f * (w_sediment + w_algae);
      const float brightness = static_cast<float>(800.0 + 200.0 * std::sin(l / 50.0));
      for (int b = 0; b < bands; ++b) {
        line[static_cast<std::size_t>(b) * samples + s] =
            empty ? nan
                  : brightness * (w_sediment * sediment[b] + w_algae * algae[b] + w_rock * rock[b]) +
                        2.0f * noise(l, b, s);
      }
    }
    writer.writeLine(line.data());
  }
  writer.finish();
  std::printf("wrote %s: %d samples x %d lines x %d bands, float32 BIL, %.3f GB\n", hdr.c_str(), samples,
              lines, bands, 4.0 * samples * lines * bands / 1e9);
  return 0;
}

int exportOrtho(const std::string& hdr, const std::string& tif, const hsmap::GeoTiffExportOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  hsmap::exportEnviToCog(hdr, tif, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("exported %s -> %s in %.2f s (%s, predictor %s, overviews %s)\n", hdr.c_str(), tif.c_str(),
              seconds, options.compression.c_str(), options.predictor ? "on" : "off",
              options.overviews ? "on" : "off");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"exportEnviToCog benchmark helper"};
  app.require_subcommand(1);

  std::string write_hdr;
  int samples = 600, lines = 4000, bands = 211;
  CLI::App* write = app.add_subcommand("write", "write a synthetic hyperspectral ortho-image (ENVI)");
  write->add_option("hdr", write_hdr, "header path (.hdr)")->required();
  write->add_option("--samples", samples, "columns")->check(CLI::PositiveNumber);
  write->add_option("--lines", lines, "rows")->check(CLI::PositiveNumber);
  write->add_option("--bands", bands, "bands")->check(CLI::PositiveNumber);

  std::string export_hdr, tif;
  hsmap::GeoTiffExportOptions options;
  bool no_overviews = false, no_predictor = false;
  CLI::App* exp = app.add_subcommand("export", "exportEnviToCog");
  exp->add_option("hdr", export_hdr, "ENVI header")->required();
  exp->add_option("tif", tif, "GeoTIFF to write")->required();
  exp->add_option("--compression", options.compression, "DEFLATE, ZSTD, LZW, LZMA or NONE");
  exp->add_option("--threads", options.threads, "compression threads, 0 = every CPU");
  exp->add_option("--block-size", options.block_size, "tile size");
  exp->add_flag("--no-overviews", no_overviews, "no overviews");
  exp->add_flag("--no-predictor", no_predictor, "no predictor");

  CLI11_PARSE(app, argc, argv);
  try {
    if (write->parsed()) return writeOrtho(write_hdr, samples, lines, bands);
    options.overviews = !no_overviews;
    options.predictor = !no_predictor;
    return exportOrtho(export_hdr, tif, options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "geotiff_export_tool: %s\n", e.what());
    return 1;
  }
}
