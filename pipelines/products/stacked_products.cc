#include "pipelines/products/stacked_products.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "core/io/envi_ignore_value.h"
#include "core/io/envi_writer.h"
#include "core/util/progress.h"
#include "pipelines/products/ortho_quicklook.h"
#include "pipelines/products/product_headers.h"

namespace hsmap {

std::string StackedReport::summary() const {
  std::ostringstream out;
  out << "stacked scan lines: " << samples << " samples x " << lines << " lines, " << bands
      << " bands, no map position; " << skipped_non_finite << " spectra NaN (a NaN/inf band), "
      << skipped_ignore_value << " NaN (data ignore value); " << seconds << " s";
  return out.str();
}

StackedReport writeStackedProducts(const EnviReader& cube, const std::vector<double>& wavelengths_nm,
                                   const std::filesystem::path& out_folder, std::ostream& log,
                                   int quicklook_max_side) {
  const auto start = std::chrono::steady_clock::now();
  const int bands = cube.bands(), samples = cube.samples(), lines = cube.lines();
  if (int(wavelengths_nm.size()) != bands) {
    throw std::invalid_argument("writeStackedProducts: " + std::to_string(wavelengths_nm.size()) +
                                " wavelengths for a cube of " + std::to_string(bands) + " bands");
  }
  const std::optional<float> ignore = enviDataIgnoreValue(cube.header(), cube.headerPath());
  std::filesystem::create_directories(out_folder);
  StackedReport report;
  report.lines = lines;
  report.samples = samples;
  report.bands = bands;
  report.ortho_hdr = out_folder / "ortho.hdr";
  report.ancillary_hdr = out_folder / "ancillary.hdr";
  report.quicklook_png = out_folder / "ortho_rgb.png";

  EnviHeader header = spectralProductHeader(cube, wavelengths_nm, lines, samples, EnviInterleave::bil);
  header.description =
      "hsmap products (stacked): the scan lines side by side, row = scan line, column = sample, "
      "values as in the cube, NaN for an invalid spectrum; no map position";
  EnviHeader ancillary = ancillaryProductHeader(lines, samples);
  ancillary.description = "hsmap products (stacked): scan line and sample of every pixel; nothing was cast";
  EnviWriter ortho_writer(report.ortho_hdr, header, EnviWriteMode::direct);
  EnviWriter ancillary_writer(report.ancillary_hdr, ancillary, EnviWriteMode::direct);
  OrthoQuicklook quicklook(lines, samples, nearestRgbBands(wavelengths_nm), quicklook_max_side);

  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> line(std::size_t(bands) * samples);  // band-major
  std::vector<float> extra(std::size_t(4) * samples);
  std::vector<std::uint8_t> invalid(static_cast<std::size_t>(samples));
  Progress progress("stacked lines", lines, "lines", log);
  for (int r = 0; r < lines; ++r) {
    cube.readLine(r, line.data());
    std::fill(invalid.begin(), invalid.end(), std::uint8_t(0));
    for (int b = 0; b < bands; ++b) {
      const float* band = line.data() + std::size_t(b) * samples;
      for (int s = 0; s < samples; ++s) {
        if (!std::isfinite(band[s])) {
          invalid[std::size_t(s)] |= 1;
        } else if (ignore && band[s] == *ignore) {
          invalid[std::size_t(s)] |= 2;
        }
      }
    }
    for (int s = 0; s < samples; ++s) {
      const std::uint8_t why = invalid[std::size_t(s)];
      if (why == 0) continue;
      ((why & 1) != 0 ? report.skipped_non_finite : report.skipped_ignore_value) += 1;
      for (int b = 0; b < bands; ++b) line[std::size_t(b) * samples + s] = kNaN;
    }
    for (int s = 0; s < samples; ++s) {
      extra[std::size_t(s)] = float(r);
      extra[std::size_t(samples) + s] = float(s);
      extra[std::size_t(2) * samples + s] = kNaN;
      extra[std::size_t(3) * samples + s] = kNaN;
    }
    ortho_writer.writeLine(line.data());
    ancillary_writer.writeLine(extra.data());
    quicklook.addRow(r, line.data());
    progress.advance();
  }
  ortho_writer.finish();
  ancillary_writer.finish();
  progress.finish();
  quicklook.write(report.quicklook_png);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace hsmap
