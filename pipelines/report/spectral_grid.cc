#include "pipelines/report/spectral_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/io/envi_reader.h"

namespace hsmap {

ReportSpectralGrid readSpectralGrid(const std::filesystem::path& ortho_hdr, long long max_blocks,
                                    long long max_values) {
  const EnviReader reader(ortho_hdr);
  const int samples = reader.samples(), lines = reader.lines(), bands = reader.bands();
  ReportSpectralGrid grid;
  grid.image_columns = samples;
  grid.image_rows = lines;
  const long long most_blocks = std::max(1LL, std::min(max_blocks, max_values / std::max(1, bands)));
  for (grid.block_px = 1;; ++grid.block_px) {
    grid.columns = (samples + grid.block_px - 1) / grid.block_px;
    grid.rows = (lines + grid.block_px - 1) / grid.block_px;
    if ((long long)grid.columns * grid.rows <= most_blocks) break;
  }
  grid.wavelengths_nm = reader.header().wavelength;
  grid.wavelengths_nm.resize(std::size_t(bands), NAN);
  grid.value_meaning = "radiance as the UHI recorded it (the cube's digital numbers), averaged over the block";

  const std::size_t cells = std::size_t(grid.columns) * std::size_t(grid.rows);
  std::vector<float> means(cells * std::size_t(bands), NAN);
  std::vector<double> sums(std::size_t(grid.columns) * std::size_t(bands));
  std::vector<int> counts(std::size_t(grid.columns));
  std::vector<float> line(std::size_t(samples) * std::size_t(bands));
  for (int block_row = 0; block_row < grid.rows; ++block_row) {
    std::fill(sums.begin(), sums.end(), 0.0);
    std::fill(counts.begin(), counts.end(), 0);
    for (int row = block_row * grid.block_px; row < std::min(lines, (block_row + 1) * grid.block_px); ++row) {
      reader.readLinePixelMajor(row, line.data());
      for (int s = 0; s < samples; ++s) {
        const float* spectrum = &line[std::size_t(s) * std::size_t(bands)];
        if (!std::all_of(spectrum, spectrum + bands, [](float v) { return std::isfinite(v); })) continue;
        const std::size_t block = std::size_t(s / grid.block_px);
        ++counts[block];
        for (int b = 0; b < bands; ++b) sums[block * std::size_t(bands) + std::size_t(b)] += spectrum[b];
      }
    }
    for (int block = 0; block < grid.columns; ++block) {
      if (counts[std::size_t(block)] == 0) continue;
      const std::size_t cell = std::size_t(block_row) * std::size_t(grid.columns) + std::size_t(block);
      for (int b = 0; b < bands; ++b) {
        means[cell * std::size_t(bands) + std::size_t(b)] =
            float(sums[std::size_t(block) * std::size_t(bands) + std::size_t(b)] / counts[std::size_t(block)]);
      }
    }
  }

  // Each band quantised to 16 bits over its own range; 65535 marks no data.
  grid.offsets.assign(std::size_t(bands), 0.0);
  grid.scales.assign(std::size_t(bands), 1.0);
  for (int b = 0; b < bands; ++b) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (std::size_t cell = 0; cell < cells; ++cell) {
      const float v = means[cell * std::size_t(bands) + std::size_t(b)];
      if (std::isnan(v)) continue;
      low = std::min(low, double(v));
      high = std::max(high, double(v));
    }
    if (!std::isfinite(low)) continue;
    grid.offsets[std::size_t(b)] = low;
    grid.scales[std::size_t(b)] = high > low ? (high - low) / 65534.0 : 1.0;
  }
  grid.values.resize(means.size());
  for (std::size_t i = 0; i < means.size(); ++i) {
    const std::size_t b = i % std::size_t(bands);
    grid.values[i] = std::isnan(means[i])
                         ? 65535
                         : (unsigned short)std::lround(std::clamp((means[i] - grid.offsets[b]) / grid.scales[b], 0.0, 65534.0));
  }
  return grid;
}

}  // namespace hsmap
