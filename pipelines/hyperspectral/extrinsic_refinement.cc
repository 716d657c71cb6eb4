#include "pipelines/hyperspectral/extrinsic_refinement.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "core/graph/factor_graph.h"
#include "core/graph/key.h"
#include "core/graph/values.h"
#include "core/io/ply_io.h"
#include "factors/extrinsic_prior_factor.h"
#include "factors/pushbroom_extrinsic_factor.h"
#include "solvers/graph_problem.h"
#include "solvers/graph_solver.h"
#include "solvers/marginal_covariance.h"
#include "solvers/robust_outliers.h"

namespace hsmap {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr double kBinWidthNm = 20.0;
constexpr double kDefaultRangeM = 2.0;

void require(bool ok, const std::string& field, const std::string& expectation, double value) {
  if (ok) return;
  std::ostringstream message;
  message << "ExtrinsicRefinementOptions: " << field << " must be " << expectation << ", got "
          << value;
  throw std::invalid_argument(message.str());
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

std::string fixed(double value, int digits) {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(digits);
  text << value;
  return text.str();
}

// Parabola through (-1, a), (0, b), (1, c): offset of the vertex in [-0.5, 0.5].
double parabolaPeak(double a, double b, double c) {
  const double denominator = a - 2.0 * b + c;
  if (!(denominator < 0.0)) return 0.0;
  return std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5);
}

// Blurred copy with NaN replaced by the mean of the valid pixels, and the
// mask (255 valid) of the original.
struct PreparedImage {
  cv::Mat blurred;  // CV_32F
  cv::Mat valid;    // CV_8U
  double stddev = 0.0;
};

PreparedImage prepare(const cv::Mat& luma, double blur_sigma_px, double highpass_sigma_px) {
  PreparedImage out;
  out.valid = cv::Mat(luma.size(), CV_8U);
  double sum = 0.0, sum2 = 0.0;
  std::int64_t n = 0;
  for (int r = 0; r < luma.rows; ++r) {
    const float* row = luma.ptr<float>(r);
    std::uint8_t* mask = out.valid.ptr<std::uint8_t>(r);
    for (int c = 0; c < luma.cols; ++c) {
      const bool ok = std::isfinite(row[c]);
      mask[c] = ok ? 255 : 0;
      if (ok) {
        sum += row[c];
        sum2 += double(row[c]) * row[c];
        ++n;
      }
    }
  }
  const double mean = n > 0 ? sum / double(n) : 0.0;
  out.stddev = n > 1 ? std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean)) : 0.0;
  out.blurred = luma.clone();
  out.blurred.setTo(cv::Scalar(mean), out.valid == 0);
  if (blur_sigma_px > 0.0) {
    cv::GaussianBlur(out.blurred, out.blurred, cv::Size(0, 0), blur_sigma_px, blur_sigma_px,
                     cv::BORDER_REFLECT);
  }
  if (highpass_sigma_px > 0.0) {
    cv::Mat background;
    cv::GaussianBlur(out.blurred, background, cv::Size(0, 0), highpass_sigma_px, highpass_sigma_px,
                     cv::BORDER_REFLECT);
    out.blurred -= background;
    cv::Scalar mean, stddev;
    cv::meanStdDev(out.blurred, mean, stddev, out.valid);
    out.stddev = stddev[0];
  }
  return out;
}

bool allValid(const cv::Mat& valid, const cv::Rect& window) {
  return cv::countNonZero(valid(window)) == window.area();
}

// p_W at continuous grid position (col, row): bilinear over the four pixels
// around it, all of which must be hits.
std::optional<Eigen::Vector3d> interpolatedPoint(const RgbOrthoRenderer& renderer,
                                                 const Eigen::Vector2d& col_row) {
  const int c0 = int(std::floor(col_row.x()));
  const int r0 = int(std::floor(col_row.y()));
  const OrthoGrid& grid = renderer.grid();
  if (c0 < 0 || r0 < 0 || c0 + 1 >= grid.cols || r0 + 1 >= grid.rows) return std::nullopt;
  const RgbOrthoPatch patch = renderer.render(c0, r0, 2, 2);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c)
      if (!patch.hit(c, r)) return std::nullopt;
  const double a = col_row.x() - c0, b = col_row.y() - r0;
  return (1 - a) * (1 - b) * patch.point(0, 0) + a * (1 - b) * patch.point(1, 0) +
         (1 - a) * b * patch.point(0, 1) + a * b * patch.point(1, 1);
}

struct LineResidual {
  double u = 0.0;       // px
  double across = 0.0;  // px (f * y / z)
};

LineResidual lineResidual(const PushbroomCamera& camera, const SE3d& T_W_C, const SE3d& T_C_U,
                          const Eigen::Vector3d& p_W, double sample) {
  const Eigen::Vector3d p_U = (T_W_C * T_C_U).inverse() * p_W;
  const Eigen::Vector2d projected = camera.project(p_U);
  return {projected.x() - sample, camera.parameters().f * projected.y()};
}

// Rotation (deg) and translation (m) of T_a^-1 T_b, for the log.
Eigen::Vector2d extrinsicChange(const SE3d& a, const SE3d& b) {
  const double angle = 2.0 * std::acos(std::min(1.0, std::abs(a.q.dot(b.q))));
  return {angle * 180.0 / std::numbers::pi, (b.t - a.t).norm()};
}

}  // namespace

void ExtrinsicRefinementOptions::validate() const {
  require(std::isfinite(band_min_nm) && std::isfinite(band_max_nm) && band_max_nm > band_min_nm,
          "band_max_nm", "above band_min_nm", band_max_nm);
  require(std::isfinite(ridge) && ridge >= 0.0, "ridge", ">= 0", ridge);
  require(fit_stride_px >= 1, "fit_stride_px", ">= 1", fit_stride_px);
  require(std::isfinite(patch_spacing_m) && patch_spacing_m > 0.0, "patch_spacing_m", "> 0",
          patch_spacing_m);
  require(std::isfinite(patch_size_m) && patch_size_m > 0.0, "patch_size_m", "> 0", patch_size_m);
  require(std::isfinite(search_radius_m) && search_radius_m > 0.0, "search_radius_m", "> 0",
          search_radius_m);
  require(std::isfinite(blur_sigma_px) && blur_sigma_px >= 0.0, "blur_sigma_px", ">= 0",
          blur_sigma_px);
  require(std::isfinite(highpass_sigma_px) && highpass_sigma_px >= 0.0, "highpass_sigma_px", ">= 0",
          highpass_sigma_px);
  require(min_ncc > -1.0 && min_ncc <= 1.0, "min_ncc", "in (-1, 1]", min_ncc);
  require(min_peak_margin >= 0.0 && min_peak_margin < 2.0, "min_peak_margin", "in [0, 2)",
          min_peak_margin);
  require(exclusion_radius_px >= 1.0, "exclusion_radius_px", ">= 1", exclusion_radius_px);
  require(min_template_std >= 0.0, "min_template_std", ">= 0", min_template_std);
  require(std::isfinite(sigma_match_m) && sigma_match_m > 0.0, "sigma_match_m", "> 0",
          sigma_match_m);
  require(std::isfinite(robust_scale) && robust_scale > 0.0, "robust_scale", "> 0", robust_scale);
  require(min_tie_points >= 1, "min_tie_points", ">= 1", min_tie_points);
  require(max_iterations >= 1, "max_iterations", ">= 1", max_iterations);
  require(num_threads >= 0, "num_threads", ">= 0", num_threads);
}

std::string ExtrinsicRefinementResult::summary() const {
  std::ostringstream out;
  out << "extrinsic refinement: " << patches << " patches, " << matches << " matches, "
      << tie_points << " tie points, " << inliers << " inliers, " << outliers
      << " outliers; median shift " << fixed(1000.0 * median_shift_m, 1) << " mm";
  if (band_fit_r2 > 0.0) out << "; band fit R^2 " << fixed(band_fit_r2, 3);
  out << "\n";
  if (!refined) {
    out << "  T_C_U kept (not refined)\n";
  } else {
    const Eigen::Vector2d change = extrinsicChange(T_C_U_initial, T_C_U);
    out << "  T_C_U moved by " << fixed(change.x(), 3) << " deg, " << fixed(1000.0 * change.y(), 1)
        << " mm; residual RMS u " << fixed(rms_u_before_px, 2) << " -> " << fixed(rms_u_after_px, 2)
        << " px, across " << fixed(rms_across_before_px, 2) << " -> "
        << fixed(rms_across_after_px, 2) << " px\n";
    if (sigma_rotation_deg && sigma_translation_m) {
      out << "  1-sigma rotation (deg, about U x y z) " << fixed((*sigma_rotation_deg)[0], 4) << " "
          << fixed((*sigma_rotation_deg)[1], 4) << " " << fixed((*sigma_rotation_deg)[2], 4)
          << ", translation (mm, along C x y z) " << fixed(1000.0 * (*sigma_translation_m)[0], 2)
          << " " << fixed(1000.0 * (*sigma_translation_m)[1], 2) << " "
          << fixed(1000.0 * (*sigma_translation_m)[2], 2) << "\n";
    }
  }
  for (const std::string& warning : warnings) out << "  warning: " << warning << "\n";
  return out.str();
}

std::vector<LinePose> updatedLinePoses(const std::vector<LinePose>& line_poses,
                                       const SE3d& T_C_U_lines, const SE3d& T_C_U_new) {
  const SE3d T_U_lines_U_new = T_C_U_lines.inverse() * T_C_U_new;
  std::vector<LinePose> out = line_poses;
  for (LinePose& pose : out) {
    pose.T = pose.T * T_U_lines_U_new;
    pose.T.q.normalize();
  }
  return out;
}

OrthoGrid orthoGridFromHeader(const EnviHeader& header) {
  if (!header.map_info || header.map_info->projection != "UTM") {
    throw std::invalid_argument("orthoGridFromHeader: the header has no UTM map info");
  }
  const EnviMapInfo& info = *header.map_info;
  if (!(info.pixel_size_x > 0.0) || std::abs(info.pixel_size_x - info.pixel_size_y) > 1e-12) {
    throw std::invalid_argument("orthoGridFromHeader: pixels must be square");
  }
  OrthoGrid grid;
  grid.pixel_m = info.pixel_size_x;
  grid.west_m = info.easting - (info.reference_pixel_x - 1.0) * grid.pixel_m;
  grid.north_m = info.northing + (info.reference_pixel_y - 1.0) * grid.pixel_m;
  grid.cols = header.samples;
  grid.rows = header.lines;
  grid.zone = info.zone;
  grid.northern = info.north;
  return grid;
}

cv::Mat rgbLuminance(const cv::Mat& bgra) {
  if (bgra.type() != CV_8UC4) throw std::invalid_argument("rgbLuminance: expected CV_8UC4");
  cv::Mat luma(bgra.size(), CV_32F);
  for (int r = 0; r < bgra.rows; ++r) {
    const cv::Vec4b* in = bgra.ptr<cv::Vec4b>(r);
    float* out = luma.ptr<float>(r);
    for (int c = 0; c < bgra.cols; ++c) {
      out[c] = in[c][3] == 0 ? kNaN : float(0.114 * in[c][0] + 0.587 * in[c][1] + 0.299 * in[c][2]);
    }
  }
  return luma;
}

BandCombination hyperspectralLuminance(const EnviReader& ortho,
                                       const std::vector<double>& wavelengths_nm,
                                       const cv::Mat& rgb_luma,
                                       const ExtrinsicRefinementOptions& options) {
  const int bands = ortho.bands(), cols = ortho.samples(), rows = ortho.lines();
  if (int(wavelengths_nm.size()) != bands) {
    throw std::invalid_argument("hyperspectralLuminance: one wavelength per band expected");
  }
  if (rgb_luma.rows != rows || rgb_luma.cols != cols || rgb_luma.type() != CV_32F) {
    throw std::invalid_argument("hyperspectralLuminance: the RGB luminance is not on the grid");
  }
  // Bands in range, in bins of kBinWidthNm.
  std::vector<int> bin_of_band(bands, -1);
  const int bins =
      std::max(1, int(std::ceil((options.band_max_nm - options.band_min_nm) / kBinWidthNm)));
  std::vector<int> bin_count(bins, 0);
  for (int b = 0; b < bands; ++b) {
    const double w = wavelengths_nm[b];
    if (w < options.band_min_nm || w > options.band_max_nm) continue;
    const int bin = std::min(bins - 1, int((w - options.band_min_nm) / kBinWidthNm));
    bin_of_band[b] = bin;
    ++bin_count[bin];
  }
  std::vector<int> used_bins;
  for (int k = 0; k < bins; ++k)
    if (bin_count[k] > 0) used_bins.push_back(k);
  if (used_bins.empty()) {
    throw std::invalid_argument("hyperspectralLuminance: no band in [band_min_nm, band_max_nm]");
  }
  const int m = int(used_bins.size());
  std::vector<int> column_of_bin(bins, -1);
  for (int i = 0; i < m; ++i) column_of_bin[used_bins[i]] = i;

  // One pass: every pixel's bin means (m floats; NaN when a band is not finite).
  std::vector<float> bin_means(std::size_t(rows) * cols * m, kNaN);
  Eigen::MatrixXf line;
  std::vector<double> sums(m);
  for (int r = 0; r < rows; ++r) {
    ortho.readLine(r, line);  // bands x cols
    for (int c = 0; c < cols; ++c) {
      std::fill(sums.begin(), sums.end(), 0.0);
      bool ok = true;
      for (int b = 0; b < bands && ok; ++b) {
        if (bin_of_band[b] < 0) continue;
        const float v = line(b, c);
        if (!std::isfinite(v)) ok = false;
        sums[column_of_bin[bin_of_band[b]]] += v;
      }
      if (!ok) continue;
      float* out = &bin_means[(std::size_t(r) * cols + c) * m];
      for (int i = 0; i < m; ++i) out[i] = float(sums[i] / bin_count[used_bins[i]]);
    }
  }

  BandCombination result;
  Eigen::VectorXd bin_weights = Eigen::VectorXd::Zero(m);
  double offset = 0.0;
  // Fixed luminance-like weights: blue < 500, green < 570, red beyond.
  for (int i = 0; i < m; ++i) {
    const double centre = options.band_min_nm + (used_bins[i] + 0.5) * kBinWidthNm;
    bin_weights[i] = centre < 500.0 ? 0.114 : centre < 570.0 ? 0.587 : 0.299;
  }
  {
    double total = bin_weights.sum();
    bin_weights /= total;
  }
  if (options.fit_band_weights) {
    // Ridge least squares of [bins, 1] -> RGB luminance on a subsample.
    Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(m + 1, m + 1);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m + 1);
    double sum_y = 0.0, sum_y2 = 0.0;
    std::int64_t n = 0;
    Eigen::VectorXd x(m + 1);
    for (int r = 0; r < rows; r += options.fit_stride_px) {
      for (int c = 0; c < cols; c += options.fit_stride_px) {
        const float y = rgb_luma.at<float>(r, c);
        const float* means = &bin_means[(std::size_t(r) * cols + c) * m];
        if (!std::isfinite(y) || !std::isfinite(means[0])) continue;
        for (int i = 0; i < m; ++i) x[i] = means[i];
        x[m] = 1.0;
        normal.selfadjointView<Eigen::Lower>().rankUpdate(x);
        rhs += x * double(y);
        sum_y += y;
        sum_y2 += double(y) * y;
        ++n;
      }
    }
    if (n >= 10 * (m + 1)) {
      normal.triangularView<Eigen::StrictlyUpper>() = normal.transpose();
      const double scale = normal.diagonal().head(m).mean();
      Eigen::MatrixXd regularised = normal;
      for (int i = 0; i < m; ++i) regularised(i, i) += options.ridge * scale;
      const Eigen::VectorXd solution = regularised.ldlt().solve(rhs);
      if (solution.allFinite()) {
        // R^2 = 1 - SSE / SST with SSE = w^T N w - 2 w^T b + sum y^2.
        const double sse = solution.dot(normal * solution) - 2.0 * solution.dot(rhs) + sum_y2;
        const double sst = sum_y2 - sum_y * sum_y / double(n);
        result.r2 = sst > 0.0 ? 1.0 - sse / sst : 0.0;
        bin_weights = solution.head(m);
        offset = solution[m];
        result.fitted = true;
      }
    }
  }
  result.offset = offset;
  result.weights.assign(bands, 0.0);
  for (int b = 0; b < bands; ++b) {
    if (bin_of_band[b] < 0) continue;
    result.weights[b] = bin_weights[column_of_bin[bin_of_band[b]]] / bin_count[bin_of_band[b]];
  }
  result.luma = cv::Mat(rows, cols, CV_32F);
  for (int r = 0; r < rows; ++r) {
    float* out = result.luma.ptr<float>(r);
    for (int c = 0; c < cols; ++c) {
      const float* means = &bin_means[(std::size_t(r) * cols + c) * m];
      if (!std::isfinite(means[0])) {
        out[c] = kNaN;
        continue;
      }
      double value = offset;
      for (int i = 0; i < m; ++i) value += bin_weights[i] * means[i];
      out[c] = float(value);
    }
  }
  return result;
}

OrthoMatchCounts matchOrthoImages(const cv::Mat& rgb_luma, const cv::Mat& hyper_luma,
                                  const cv::Mat& ancillary, const RgbOrthoRenderer& renderer,
                                  const ExtrinsicRefinementOptions& options,
                                  std::vector<ExtrinsicTiePoint>& tie_points) {
  options.validate();
  const OrthoGrid& grid = renderer.grid();
  if (rgb_luma.size() != hyper_luma.size() || rgb_luma.rows != grid.rows ||
      rgb_luma.cols != grid.cols || ancillary.size() != rgb_luma.size() ||
      ancillary.type() != CV_32FC4) {
    throw std::invalid_argument("matchOrthoImages: the images are not on the renderer's grid");
  }
  const PreparedImage rgb = prepare(rgb_luma, options.blur_sigma_px, options.highpass_sigma_px);
  const PreparedImage hyper = prepare(hyper_luma, options.blur_sigma_px, options.highpass_sigma_px);
  const int half = std::max(2, int(std::lround(0.5 * options.patch_size_m / grid.pixel_m)));
  const int radius = std::max(2, int(std::lround(options.search_radius_m / grid.pixel_m)));
  const int step = std::max(1, int(std::lround(options.patch_spacing_m / grid.pixel_m)));
  const int size = 2 * half + 1;
  const int margin = half + radius;
  const double exclusion2 = options.exclusion_radius_px * options.exclusion_radius_px;
  const double min_std = options.min_template_std * rgb.stddev;

  OrthoMatchCounts counts;
  cv::Mat scores;
  for (int cy = margin; cy + margin < grid.rows; cy += step) {
    for (int cx = margin; cx + margin < grid.cols; cx += step) {
      ++counts.patches;
      const cv::Rect templ_rect(cx - half, cy - half, size, size);
      const cv::Rect search_rect(cx - margin, cy - margin, size + 2 * radius, size + 2 * radius);
      if (!allValid(rgb.valid, templ_rect) || !allValid(hyper.valid, search_rect)) continue;
      const cv::Mat templ = rgb.blurred(templ_rect);
      cv::Scalar mean, stddev;
      cv::meanStdDev(templ, mean, stddev);
      if (stddev[0] < min_std || stddev[0] <= 0.0) continue;
      ++counts.textured;
      cv::matchTemplate(hyper.blurred(search_rect), templ, scores, cv::TM_CCOEFF_NORMED);
      double best = 0.0;
      cv::Point peak;
      cv::minMaxLoc(scores, nullptr, &best, nullptr, &peak);
      if (!(best >= options.min_ncc)) continue;
      if (peak.x <= 0 || peak.y <= 0 || peak.x >= scores.cols - 1 || peak.y >= scores.rows - 1) {
        continue;
      }
      double second = -1.0;
      for (int r = 0; r < scores.rows; ++r) {
        const float* row = scores.ptr<float>(r);
        for (int c = 0; c < scores.cols; ++c) {
          const double d2 = double(c - peak.x) * (c - peak.x) + double(r - peak.y) * (r - peak.y);
          if (d2 > exclusion2) second = std::max(second, double(row[c]));
        }
      }
      if (second > best - options.min_peak_margin) continue;
      const double dx =
          parabolaPeak(scores.at<float>(peak.y, peak.x - 1), scores.at<float>(peak.y, peak.x),
                       scores.at<float>(peak.y, peak.x + 1));
      const double dy =
          parabolaPeak(scores.at<float>(peak.y - 1, peak.x), scores.at<float>(peak.y, peak.x),
                       scores.at<float>(peak.y + 1, peak.x));
      ++counts.matched;
      const Eigen::Vector2d g(cx, cy);
      const Eigen::Vector2d h = g + Eigen::Vector2d(peak.x + dx - radius, peak.y + dy - radius);
      // Nearest-pixel ancillary; the RGB side moved by the same rounding.
      const Eigen::Vector2i h_pixel(int(std::lround(h.x())), int(std::lround(h.y())));
      if (!grid.contains(h_pixel)) continue;
      const cv::Vec4f& anc = ancillary.at<cv::Vec4f>(h_pixel.y(), h_pixel.x());
      if (!std::isfinite(anc[0]) || !std::isfinite(anc[1])) continue;
      const Eigen::Vector2d g_moved = g + (h_pixel.cast<double>() - h);
      const std::optional<Eigen::Vector3d> p_W = interpolatedPoint(renderer, g_moved);
      if (!p_W) continue;
      ExtrinsicTiePoint tie;
      tie.line = std::llround(anc[0]);
      tie.sample = anc[1];
      tie.range_m = std::isfinite(anc[2]) ? anc[2] : 0.0;
      tie.p_W = *p_W;
      tie.rgb_col_row = g;
      tie.hyper_col_row = h;
      tie.ncc = best;
      tie_points.push_back(tie);
      ++counts.tie_points;
    }
  }
  return counts;
}

ExtrinsicRefinementResult refineExtrinsicFromTiePoints(
    const std::vector<ExtrinsicTiePoint>& tie_points, const std::vector<LinePose>& line_poses,
    const SE3d& T_C_U_lines, const PushbroomParameters& camera_parameters,
    const ExtrinsicPrior& prior, const ExtrinsicRefinementOptions& options) {
  options.validate();
  const PushbroomCamera camera(camera_parameters);
  ExtrinsicRefinementResult result;
  result.T_C_U_initial = T_C_U_lines;
  result.T_C_U = T_C_U_lines;
  result.tie_points = std::int64_t(tie_points.size());

  std::unordered_map<long long, const LinePose*> pose_of_line;
  for (const LinePose& pose : line_poses) pose_of_line[pose.line] = &pose;
  const SE3d T_U_C_lines = T_C_U_lines.inverse();

  // The usable tie points and their line camera poses.
  struct Tie {
    const ExtrinsicTiePoint* tie;
    SE3d T_W_C;
  };
  std::vector<Tie> ties;
  std::int64_t without_line = 0;
  for (const ExtrinsicTiePoint& tie : tie_points) {
    const auto found = pose_of_line.find(tie.line);
    if (found == pose_of_line.end() || !tie.p_W.allFinite() || !std::isfinite(tie.sample)) {
      ++without_line;
      continue;
    }
    ties.push_back({&tie, found->second->T * T_U_C_lines});
  }
  if (without_line > 0) {
    result.warnings.push_back(std::to_string(without_line) +
                              " tie points skipped: line without pose or non-finite values");
  }
  if (int(ties.size()) < options.min_tie_points) {
    result.warnings.push_back("only " + std::to_string(ties.size()) + " usable tie points (< " +
                              std::to_string(options.min_tie_points) +
                              "): T_C_U kept at the line poses' extrinsic (the prior alone "
                              "cannot improve it)");
    return result;
  }

  const NoiseModel prior_noise =
      ExtrinsicPriorFactor::noiseFromSigmas(prior.sigma_rotation_deg, prior.sigma_translation_m);
  auto buildGraph = [&](const std::vector<bool>& keep) {
    FactorGraph graph;
    graph.emplace<ExtrinsicPriorFactor>(E(0), prior.T_C_U, prior_noise);
    for (std::size_t i = 0; i < ties.size(); ++i) {
      if (!keep[i]) continue;
      const ExtrinsicTiePoint& tie = *ties[i].tie;
      const double range = tie.range_m > 0.0 ? tie.range_m : kDefaultRangeM;
      const double sigma_across = options.sigma_match_m / range;
      const Eigen::Vector2d sigmas(camera_parameters.f * sigma_across, sigma_across);
      graph.emplace<PushbroomExtrinsicFactor>(E(0), ties[i].T_W_C, tie.p_W, tie.sample,
                                              camera_parameters, NoiseModel::fromSigmas(sigmas),
                                              RobustLoss::cauchy(options.robust_scale));
    }
    return graph;
  };

  Values values;
  values.insertPose(E(0), T_C_U_lines.q, T_C_U_lines.t);
  SolverOptions solver;
  solver.linear_solver = SolverOptions::LinearSolver::sparse_normal_cholesky;
  solver.max_iterations = options.max_iterations;
  solver.num_threads = options.num_threads;

  // First solve with every tie point; the factors beyond the loss scale are outliers.
  std::vector<bool> keep(ties.size(), true);
  {
    const FactorGraph graph = buildGraph(keep);
    GraphProblem problem(graph, values);
    solve(problem, solver);
    for (const std::size_t index : factorsBeyondLossScale(problem)) {
      keep[index - 1] = false;  // factor 0 is the prior
      ++result.outliers;
    }
  }
  result.inliers = std::int64_t(std::count(keep.begin(), keep.end(), true));
  if (result.inliers < options.min_tie_points) {
    result.warnings.push_back("only " + std::to_string(result.inliers) +
                              " inliers: T_C_U kept at the line poses' extrinsic");
    return result;
  }
  // Final solve on the inliers, from the first solve's estimate.
  const FactorGraph graph = buildGraph(keep);
  GraphProblem problem(graph, values);
  const SolveReport report = solve(problem, solver);
  result.solve_report = report.toString();
  if (!report.usable) {
    result.warnings.push_back("the solve failed: T_C_U kept (" + report.reason + ")");
    return result;
  }
  result.T_C_U = SE3d(values.poseRotation(E(0)).normalized(), values.poseTranslation(E(0)));
  result.refined = true;
  try {
    CovarianceOptions covariance_options;
    covariance_options.algorithm = CovarianceOptions::Algorithm::dense_svd;
    const Eigen::MatrixXd covariance =
        marginalCovariances(problem, {E(0)}, covariance_options).at(E(0));
    const Eigen::Matrix3d R_C_U = result.T_C_U.q.toRotationMatrix();
    const Eigen::Matrix3d translation_C =
        R_C_U * covariance.topLeftCorner<3, 3>() * R_C_U.transpose();
    result.sigma_translation_m = translation_C.diagonal().cwiseMax(0.0).cwiseSqrt();
    result.sigma_rotation_deg =
        Eigen::Vector3d(covariance.bottomRightCorner<3, 3>().diagonal().cwiseMax(0.0).cwiseSqrt() *
                        (180.0 / std::numbers::pi));
  } catch (const std::exception& error) {
    result.warnings.push_back(std::string("no covariance: ") + error.what());
  }

  // Residual RMS over the inliers, before and after.
  double su0 = 0, sa0 = 0, su1 = 0, sa1 = 0;
  for (std::size_t i = 0; i < ties.size(); ++i) {
    if (!keep[i]) continue;
    const ExtrinsicTiePoint& tie = *ties[i].tie;
    const LineResidual before =
        lineResidual(camera, ties[i].T_W_C, T_C_U_lines, tie.p_W, tie.sample);
    const LineResidual after =
        lineResidual(camera, ties[i].T_W_C, result.T_C_U, tie.p_W, tie.sample);
    su0 += before.u * before.u;
    sa0 += before.across * before.across;
    su1 += after.u * after.u;
    sa1 += after.across * after.across;
    result.used.push_back(tie);
  }
  const double n = double(result.inliers);
  result.rms_u_before_px = std::sqrt(su0 / n);
  result.rms_across_before_px = std::sqrt(sa0 / n);
  result.rms_u_after_px = std::sqrt(su1 / n);
  result.rms_across_after_px = std::sqrt(sa1 / n);
  return result;
}

RunTiePoints collectTiePointsInRun(const std::filesystem::path& run,
                                   const UtmProjection& projection,
                                   const ExtrinsicRefinementOptions& options, std::ostream& log) {
  options.validate();
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  const EnviReader ortho(run / "hyperspectral" / "ortho.hdr");
  const EnviReader ancillary_reader(run / "hyperspectral" / "ancillary.hdr");
  const OrthoGrid grid = orthoGridFromHeader(ortho.header());
  if (ancillary_reader.samples() != grid.cols || ancillary_reader.lines() != grid.rows ||
      ancillary_reader.bands() < 3) {
    throw std::runtime_error(
        "collectTiePointsInRun: " + (run / "hyperspectral" / "ancillary.hdr").string() +
        " is not on the ortho-image's grid or has fewer than 3 bands");
  }

  // The RGB ortho-image and its points, from the mesh.
  const PlyMesh mesh = readPly(run / "map" / "mesh.ply");
  const RgbOrthoRenderer renderer(mesh, grid, projection);
  cv::Mat bgra;
  renderer.renderColours(0, 0, grid.cols, grid.rows, bgra);
  const cv::Mat rgb_luma = rgbLuminance(bgra);
  log << "tie points: RGB ortho rendered (" << grid.cols << " x " << grid.rows << "), "
      << fixed(seconds(), 1) << " s\n";

  RunTiePoints out;
  BandCombination combination =
      hyperspectralLuminance(ortho, ortho.header().wavelength, rgb_luma, options);
  log << "tie points: hyperspectral luminance ("
      << (combination.fitted ? "fitted, R^2 " + fixed(combination.r2, 3)
                             : std::string("fixed weights"))
      << "), " << fixed(seconds(), 1) << " s\n";

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
  log << "tie points: " << out.counts.patches << " patches, " << out.counts.textured
      << " textured, " << out.counts.matched << " matched, " << out.counts.tie_points
      << " tie points, " << fixed(seconds(), 1) << " s\n";
  combination.luma.release();
  out.combination = std::move(combination);
  std::vector<double> shifts;
  for (const ExtrinsicTiePoint& tie : out.tie_points) {
    shifts.push_back((tie.hyper_col_row - tie.rgb_col_row).norm() * grid.pixel_m);
  }
  out.median_shift_m = median(shifts);
  return out;
}

ExtrinsicRefinementResult refineExtrinsicInRun(
    const std::filesystem::path& run, const SE3d& T_C_U_lines, const PushbroomParameters& camera,
    const ExtrinsicPrior& prior, const UtmProjection& projection,
    const ExtrinsicRefinementOptions& options, std::ostream& log) {
  const std::vector<LinePose> line_poses = readLinePoseTable(run / "trajectory" / "uhi_lines.csv");
  const RunTiePoints found = collectTiePointsInRun(run, projection, options, log);
  ExtrinsicRefinementResult result = refineExtrinsicFromTiePoints(
      found.tie_points, line_poses, T_C_U_lines, camera, prior, options);
  result.patches = found.counts.patches;
  result.matches = found.counts.matched;
  result.band_weights = found.combination.weights;
  result.band_offset = found.combination.offset;
  result.band_fit_r2 = found.combination.fitted ? found.combination.r2 : 0.0;
  result.median_shift_m = found.median_shift_m;
  log << result.summary();
  return result;
}

}  // namespace hsmap
