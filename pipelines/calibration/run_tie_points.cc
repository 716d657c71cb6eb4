#include "pipelines/calibration/run_tie_points.h"

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <limits>
#include <opencv2/core.hpp>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/io/envi_reader.h"
#include "core/io/ply_io.h"
#include "core/util/median.h"
#include "core/util/message_text.h"
#include "pipelines/products/ortho_grid_from_header.h"
#include "pipelines/products/rgb_ortho.h"

namespace hsmap {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

}  // namespace

RunTiePoints collectOrthoTiePoints(const std::filesystem::path& ortho_folder, const PlyMesh& mesh,
                                   const UtmProjection& projection,
                                   const ExtrinsicRefinementOptions& options, std::ostream& log) {
  options.validate();
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  const EnviReader ortho(ortho_folder / "ortho.hdr");
  const EnviReader ancillary_reader(ortho_folder / "ancillary.hdr");
  const OrthoGrid grid = orthoGridFromHeader(ortho.header());
  if (ancillary_reader.samples() != grid.cols || ancillary_reader.lines() != grid.rows ||
      ancillary_reader.bands() < 3) {
    throw std::runtime_error(
        "collectOrthoTiePoints: " + (ortho_folder / "ancillary.hdr").string() +
        " is not on the ortho-image's grid or has fewer than 3 bands");
  }

  // The RGB ortho-image and its points, from the mesh.
  const RgbOrthoRenderer renderer(mesh, grid, projection);
  cv::Mat bgra;
  renderer.renderColours(0, 0, grid.cols, grid.rows, bgra);
  const cv::Mat rgb_luma = rgbLuminance(bgra);
  log << "tie points: RGB ortho rendered (" << grid.cols << " x " << grid.rows << "), "
      << fixedDecimals(seconds(), 1) << " s\n";

  RunTiePoints out;
  BandCombination combination =
      hyperspectralLuminance(ortho, ortho.header().wavelength, rgb_luma, options);
  log << "tie points: hyperspectral luminance ("
      << (combination.fitted ? "fitted, R^2 " + fixedDecimals(combination.r2, 3)
                             : std::string("fixed weights"))
      << "), " << fixedDecimals(seconds(), 1) << " s\n";

  cv::Mat ancillary(grid.rows, grid.cols, CV_32FC4, cv::Scalar::all(kNaN));
  Eigen::MatrixXf line;
  for (int r = 0; r < grid.rows; ++r) {
    ancillary_reader.readLine(r, line);
    cv::Vec4f* row = ancillary.ptr<cv::Vec4f>(r);
    for (int c = 0; c < grid.cols; ++c) {
      for (int b = 0; b < 4 && b < ancillary_reader.bands(); ++b) row[c][b] = line(b, c);
    }
  }

  out.counts = matchOrthoImages(rgb_luma, combination.luma, ancillary, renderer, options,
                                out.tie_points);
  log << "tie points: coarse step " << out.counts.coarse_matched << " of "
      << out.counts.coarse_patches << " large patches matched"
      << (out.counts.coarse_scale < 1.0 ? " (at half size: the swath is narrow)" : "") << "; "
      << out.counts.patches
      << " patches, " << out.counts.textured << " textured (" << out.counts.shifted
      << " searched around a coarse shift), " << out.counts.matched << " matched, "
      << out.counts.tie_points << " tie points, " << fixedDecimals(seconds(), 1) << " s\n";
  combination.luma.release();
  out.combination = std::move(combination);
  std::vector<double> shifts;
  for (const ExtrinsicTiePoint& tie : out.tie_points) {
    shifts.push_back((tie.hyper_col_row - tie.rgb_col_row).norm() * grid.pixel_m);
  }
  out.median_shift_m = upperMedian(shifts);
  return out;
}

}  // namespace hsmap
