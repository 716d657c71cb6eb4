#pragma once
// OrthoQuicklook: RUN/hyperspectral/ortho_rgb.png, a colour preview of the
// hyperspectral ortho-image built while its rows are written (the cube is
// never read back).
//
// Bands: the ones nearest 640 (red), 550 (green) and 460 nm (blue)
// (nearestRgbBands). Size: the ortho-image's, or reduced by a whole factor k
// (the smallest making both sides <= max_side) with each k x k block the
// mean of its non-NaN pixels, so memory stays bounded for long surveys.
// Stretch: per channel, the 2nd and 98th percentiles of the preview's valid
// values map to 0 and 255 (clamped). Pixels with any channel NaN are black.
// Written atomically (encoded in memory, AtomicFile).

#include <array>
#include <filesystem>
#include <vector>

namespace hsmap {

// Indices of the bands nearest 640, 550 and 460 nm (R, G, B).
// std::invalid_argument for an empty list.
std::array<int, 3> nearestRgbBands(const std::vector<double>& wavelengths_nm);

class OrthoQuicklook {
 public:
  OrthoQuicklook(int rows, int cols, std::array<int, 3> rgb_bands, int max_side = 8192);

  int factor() const { return factor_; }
  int previewRows() const { return rows_; }
  int previewCols() const { return cols_; }

  // Row `row` of the ortho-image, band-major (out[b * cols + c] as OrthoTileAccumulator::spectraRow).
  void addRow(int row, const float* band_major_row);

  // Stretches and writes the PNG; std::runtime_error when it cannot.
  void write(const std::filesystem::path& png_path) const;

 private:
  int full_cols_, factor_, rows_, cols_;
  std::array<int, 3> bands_;
  std::vector<float> sums_;   // [(r * cols + c) * 3 + channel]
  std::vector<int> counts_;
};

}  // namespace hsmap
