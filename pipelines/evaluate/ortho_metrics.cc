#include "pipelines/evaluate/ortho_metrics.h"

#include "core/io/envi_ignore_value.h"
#include "pipelines/evaluate/band_limited_phase_correlation.h"
#include "pipelines/evaluate/ortho_coarse_similarity.h"
#include "pipelines/evaluate/ortho_raster_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include <Eigen/Dense>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/geometry/utm_projection.h"
#include "core/io/envi_reader.h"
#include "core/util/input_error.h"
#include "pipelines/evaluate/true_surface_samples.h"

namespace hsmap {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The W -> UTM map is evaluated exactly every kNodeStep truth pixels.
constexpr int kNodeStep = 16;

bool validValue(float v, const std::optional<float>& ignore) {
  return std::isfinite(v) && !(ignore && v == *ignore);
}

// Mean over the valid bands of every pixel (NaN where none is), streamed
// line by line.
cv::Mat bandMeanImage(const EnviReader& reader, const std::optional<float>& ignore) {
  cv::Mat mean(reader.lines(), reader.samples(), CV_32F);
  Eigen::MatrixXf line;  // bands x samples
  for (int r = 0; r < reader.lines(); ++r) {
    reader.readLine(r, line);
    float* out = mean.ptr<float>(r);
    for (int c = 0; c < reader.samples(); ++c) {
      double sum = 0;
      int count = 0;
      for (int b = 0; b < reader.bands(); ++b) {
        const float v = line(b, c);
        if (!validValue(v, ignore)) continue;
        sum += v;
        ++count;
      }
      out[c] = count > 0 ? static_cast<float>(sum / count) : kNaN;
    }
  }
  return mean;
}

// Truth pixel (continuous row, col) -> produced pixel (continuous col, row),
// through an affine map of W's (east, north) applied first (identity: the
// produced raster as placed; a similarity: at the registered position).
// Exact every kNodeStep pixels, bilinear in between (linear beyond the last
// nodes).
class ProducedLookup {
 public:
  ProducedLookup(const RasterGrid& truth, const RasterGrid& produced, const UtmProjection& utm,
                 double down, const Eigen::Matrix2d& A = Eigen::Matrix2d::Identity(),
                 const Eigen::Vector2d& b = Eigen::Vector2d::Zero()) {
    node_rows_ = std::max(2, (truth.rows - 1 + kNodeStep - 1) / kNodeStep + 1);
    node_cols_ = std::max(2, (truth.cols - 1 + kNodeStep - 1) / kNodeStep + 1);
    nodes_.resize(static_cast<std::size_t>(node_rows_) * node_cols_);
    for (int i = 0; i < node_rows_; ++i) {
      for (int j = 0; j < node_cols_; ++j) {
        const Eigen::Vector2d en = A * truth.centre(i * kNodeStep, j * kNodeStep) + b;
        const Eigen::Vector2d utm_en = utm.nedToUtm(Eigen::Vector3d(en.y(), en.x(), down));
        nodes_[static_cast<std::size_t>(i) * node_cols_ + j] = produced.pixel(utm_en);
      }
    }
  }

  Eigen::Vector2d at(double row, double col) const {
    const double u = row / kNodeStep, v = col / kNodeStep;
    const int i = std::clamp(static_cast<int>(std::floor(u)), 0, node_rows_ - 2);
    const int j = std::clamp(static_cast<int>(std::floor(v)), 0, node_cols_ - 2);
    const double fu = u - i, fv = v - j;
    const auto node = [&](int a, int c) -> const Eigen::Vector2d& {
      return nodes_[static_cast<std::size_t>(a) * node_cols_ + c];
    };
    return (1 - fu) * ((1 - fv) * node(i, j) + fv * node(i, j + 1)) +
           fu * ((1 - fv) * node(i + 1, j) + fv * node(i + 1, j + 1));
  }

 private:
  int node_rows_ = 0, node_cols_ = 0;
  std::vector<Eigen::Vector2d> nodes_;  // (col, row) in the produced raster
};

// Bilinear sample at (col, row); NaN outside or when a neighbour is NaN.
double sampleBilinear(const cv::Mat& image, const Eigen::Vector2d& col_row) {
  const double x = col_row.x(), y = col_row.y();
  if (!(x >= 0.0 && y >= 0.0 && x <= image.cols - 1 && y <= image.rows - 1)) return kNaN;
  const int c0 = std::min(static_cast<int>(x), std::max(0, image.cols - 2));
  const int r0 = std::min(static_cast<int>(y), std::max(0, image.rows - 2));
  const int c1 = std::min(c0 + 1, image.cols - 1), r1 = std::min(r0 + 1, image.rows - 1);
  const double fx = x - c0, fy = y - r0;
  const double v00 = image.at<float>(r0, c0), v01 = image.at<float>(r0, c1);
  const double v10 = image.at<float>(r1, c0), v11 = image.at<float>(r1, c1);
  return (1 - fy) * ((1 - fx) * v00 + fx * v01) + fy * ((1 - fx) * v10 + fx * v11);
}

// Nearest pixel (row, col) of a continuous (col, row), or nullopt outside.
std::optional<std::pair<int, int>> nearestPixel(const Eigen::Vector2d& col_row, int rows, int cols) {
  const double c = std::round(col_row.x()), r = std::round(col_row.y());
  if (!(c >= 0 && r >= 0 && c < cols && r < rows)) return std::nullopt;
  return std::make_pair(static_cast<int>(r), static_cast<int>(c));
}

// The produced mean image on `size` truth pixels from (r0, c0), sampled at
// truth position + (d_row, d_col) pixels, as CV_64F.
cv::Mat resampleProduced(const cv::Mat& produced_mean, const ProducedLookup& lookup, int r0, int c0,
                         cv::Size size, double d_row, double d_col) {
  cv::Mat out(size, CV_64F);
  for (int i = 0; i < size.height; ++i) {
    double* row = out.ptr<double>(i);
    for (int j = 0; j < size.width; ++j) {
      row[j] = sampleBilinear(produced_mean, lookup.at(r0 + i + d_row, c0 + j + d_col));
    }
  }
  return out;
}

double validFraction(const cv::Mat& image) {
  int valid = 0;
  for (int i = 0; i < image.rows; ++i) {
    const double* row = image.ptr<double>(i);
    for (int j = 0; j < image.cols; ++j) valid += std::isnan(row[j]) ? 0 : 1;
  }
  return static_cast<double>(valid) / image.total();
}

// In place: mean 0 and unit standard deviation over the valid pixels, NaN
// set to 0. False for a featureless image (standard deviation ~0).
bool normalise(cv::Mat& image) {
  double sum = 0, sum2 = 0;
  int count = 0;
  for (int i = 0; i < image.rows; ++i) {
    const double* row = image.ptr<double>(i);
    for (int j = 0; j < image.cols; ++j) {
      if (std::isnan(row[j])) continue;
      sum += row[j];
      ++count;
    }
  }
  if (count < 2) return false;
  const double mean = sum / count;
  for (int i = 0; i < image.rows; ++i) {
    const double* row = image.ptr<double>(i);
    for (int j = 0; j < image.cols; ++j) {
      if (!std::isnan(row[j])) sum2 += (row[j] - mean) * (row[j] - mean);
    }
  }
  const double sd = std::sqrt(sum2 / count);
  // float32 data: below ~1e-6 of the level the variation is rounding.
  if (!(sd > 1e-6 * std::max(std::abs(mean), 1e-30))) return false;
  for (int i = 0; i < image.rows; ++i) {
    double* row = image.ptr<double>(i);
    for (int j = 0; j < image.cols; ++j) row[j] = std::isnan(row[j]) ? 0.0 : (row[j] - mean) / sd;
  }
  return true;
}

struct PatchResult {
  bool has_data = false;
  bool matched = false;
  Eigen::Vector2d displacement_px = Eigen::Vector2d::Zero();  // (d_row, d_col)
  double response = 0;
};

PatchResult measurePatch(const cv::Mat& truth_mean, const cv::Mat& produced_mean,
                         const ProducedLookup& lookup, const cv::Mat& hann, int r0, int c0, int side,
                         const Eigen::Vector2d& start_px, double pixel_m,
                         const OrthoMetricsOptions& options) {
  PatchResult result;
  const cv::Size size(side, side);
  cv::Mat truth;
  truth_mean(cv::Rect(c0, r0, side, side)).convertTo(truth, CV_64F);
  Eigen::Vector2d offset = start_px;  // (d_row, d_col)
  cv::Mat produced = resampleProduced(produced_mean, lookup, r0, c0, size, offset.x(), offset.y());
  if (validFraction(truth) < options.min_valid_fraction ||
      validFraction(produced) < options.min_valid_fraction) {
    return result;
  }
  result.has_data = true;
  if (!normalise(truth)) return result;
  const double cutoff_px = options.correlation_cutoff_m / pixel_m;
  double last_correction = std::numeric_limits<double>::infinity();
  // The refined estimates (after the first correction) wander about the
  // displacement by the estimator's noise; their mean is the measurement.
  Eigen::Vector2d sum_refined = Eigen::Vector2d::Zero();
  int refined = 0;
  for (int iteration = 0; iteration <= options.max_refinements; ++iteration) {
    if (iteration > 0) {
      produced = resampleProduced(produced_mean, lookup, r0, c0, size, offset.x(), offset.y());
      if (validFraction(produced) < options.min_valid_fraction) return result;
    }
    if (!normalise(produced)) return result;
    // The shift of `produced` relative to `truth`: produced(x) = truth(x - s).
    const PhaseCorrelation correlation = bandLimitedPhaseCorrelate(truth, produced, hann, cutoff_px);
    const cv::Point2d s = correlation.shift;
    const double response = correlation.response;
    offset += Eigen::Vector2d(s.y, s.x);
    if (iteration >= 1) {
      sum_refined += offset;
      ++refined;
    }
    result.response = response;
    last_correction = std::hypot(s.x, s.y);
    // Beyond half a patch the correlation wraps around: not a measurement.
    if ((offset - start_px).norm() > 0.5 * side) return result;
    if (last_correction < options.refinement_tolerance_px) break;
  }
  result.displacement_px = refined > 0 ? Eigen::Vector2d(sum_refined / refined) : offset;
  result.matched = result.response >= options.min_response && last_correction <= 0.5;
  return result;
}

// The first match found again on the window shifted diagonally by a quarter
// patch (ortho_metrics.h, step 3): the first direction inside the raster
// with data decides.
// Displacements are compared after the coarse warp's linear part
// `warp_rc` (on (row, col) pixel vectors): as differences on the truth grid.
bool confirmMatch(const PatchResult& first, const cv::Mat& truth_mean, const cv::Mat& produced_mean,
                  const ProducedLookup& lookup, const cv::Mat& hann, int r0, int c0, int side,
                  const Eigen::Vector2d& start_px, double pixel_m, double tolerance_px,
                  const Eigen::Matrix2d& warp_rc, const OrthoMetricsOptions& options) {
  const int quarter = std::max(1, side / 4);
  for (const auto& [dr, dc] : {std::pair{1, 1}, std::pair{1, -1}, std::pair{-1, 1}, std::pair{-1, -1}}) {
    const int r = r0 + dr * quarter, c = c0 + dc * quarter;
    if (r < 0 || c < 0 || r + side > truth_mean.rows || c + side > truth_mean.cols) continue;
    const PatchResult second =
        measurePatch(truth_mean, produced_mean, lookup, hann, r, c, side, start_px, pixel_m, options);
    if (!second.has_data) continue;
    return second.matched &&
           (warp_rc * (second.displacement_px - first.displacement_px)).norm() <= tolerance_px;
  }
  return false;
}

// Coarse whole-image shift (d_row, d_col) in truth pixels, when confident.
std::optional<Eigen::Vector2d> coarseShift(const cv::Mat& truth_mean, const cv::Mat& produced_on_truth,
                                           const OrthoMetricsOptions& options) {
  cv::Mat truth, produced;
  truth_mean.convertTo(truth, CV_64F);
  produced_on_truth.convertTo(produced, CV_64F);
  if (!normalise(truth) || !normalise(produced)) return std::nullopt;
  const int longest = std::max(truth.rows, truth.cols);
  const double factor = std::max(1.0, std::ceil(static_cast<double>(longest) / options.coarse_max_side));
  const cv::Size coarse(static_cast<int>(truth.cols / factor), static_cast<int>(truth.rows / factor));
  if (coarse.width < 8 || coarse.height < 8) return std::nullopt;
  if (coarse != truth.size()) {
    cv::resize(truth, truth, coarse, 0, 0, cv::INTER_AREA);
    cv::resize(produced, produced, coarse, 0, 0, cv::INTER_AREA);
  }
  cv::Mat hann;
  cv::createHanningWindow(hann, coarse, CV_64F);
  const PhaseCorrelation correlation = bandLimitedPhaseCorrelate(truth, produced, hann, 0.0);
  const cv::Point2d s = correlation.shift;
  if (!(correlation.response >= options.coarse_min_response)) return std::nullopt;
  return Eigen::Vector2d(s.y * truth_mean.rows / coarse.height, s.x * truth_mean.cols / coarse.width);
}

// Least-squares 2-D similarity b = M a + t, M = [[p, -q], [q, p]], on
// (east, north) points: linear in (p, q, t), solved in closed form about the
// centroids.
struct Similarity2d {
  Eigen::Matrix2d M = Eigen::Matrix2d::Identity();
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  double scale() const { return std::hypot(M(0, 0), M(1, 0)); }
  double rotationDeg() const { return std::atan2(M(1, 0), M(0, 0)) * 180.0 / std::numbers::pi; }
};

std::optional<Similarity2d> fitSimilarity(const std::vector<Eigen::Vector2d>& a,
                                          const std::vector<Eigen::Vector2d>& b) {
  Eigen::Vector2d mean_a = Eigen::Vector2d::Zero(), mean_b = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) {
    mean_a += a[i];
    mean_b += b[i];
  }
  mean_a /= static_cast<double>(a.size());
  mean_b /= static_cast<double>(b.size());
  double dot = 0, cross = 0, norm2 = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Eigen::Vector2d u = a[i] - mean_a, v = b[i] - mean_b;
    dot += u.dot(v);
    cross += u.x() * v.y() - u.y() * v.x();
    norm2 += u.squaredNorm();
  }
  if (!(norm2 > 0.0)) return std::nullopt;
  Similarity2d S;
  const double p = dot / norm2, q = cross / norm2;
  S.M << p, -q, q, p;
  S.t = mean_b - S.M * mean_a;
  return S;
}

std::string formatFigure(const MetricValue& value) {
  if (!value.value) return "null (" + value.reason + ")";
  std::ostringstream out;
  out.precision(6);
  out << *value.value;
  return out.str();
}

struct SamResult {
  std::int64_t pixels = 0;
  double sum_deg = 0;
};

// Spectral angle between the truth lattice pixels and the nearest produced
// pixel through `lookup` (header comment).
SamResult spectralAngle(const EnviReader& truth, const EnviReader& produced,
                        const std::optional<float>& ignore, const ProducedLookup& lookup, int stride,
                        std::int64_t chunk_bytes) {
  const int bands = truth.bands();
  const int lattice_cols = (truth.samples() + stride - 1) / stride;
  const std::int64_t row_bytes = static_cast<std::int64_t>(lattice_cols) * bands * sizeof(float);
  const int chunk_rows = static_cast<int>(std::max<std::int64_t>(1, chunk_bytes / row_bytes));

  struct Entry {
    int produced_row, produced_col;
    std::size_t slot;  // spectrum index in `spectra`
  };
  SamResult result;
  Eigen::MatrixXf line, produced_line;
  std::vector<float> spectra;
  std::vector<Entry> entries;
  for (int first = 0; first < truth.lines(); first += chunk_rows * stride) {
    spectra.clear();
    entries.clear();
    for (int r = first; r < std::min(truth.lines(), first + chunk_rows * stride); r += stride) {
      truth.readLine(r, line);
      for (int c = 0; c < truth.samples(); c += stride) {
        bool valid = true;
        for (int b = 0; b < bands && valid; ++b) valid = std::isfinite(line(b, c));
        if (!valid) continue;
        const auto pixel = nearestPixel(lookup.at(r, c), produced.lines(), produced.samples());
        if (!pixel) continue;
        entries.push_back({pixel->first, pixel->second, spectra.size() / bands});
        for (int b = 0; b < bands; ++b) spectra.push_back(line(b, c));
      }
    }
    std::sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) {
      return x.produced_row != y.produced_row ? x.produced_row < y.produced_row
                                              : x.produced_col < y.produced_col;
    });
    int loaded = -1;
    for (const Entry& entry : entries) {
      if (entry.produced_row != loaded) {
        produced.readLine(entry.produced_row, produced_line);
        loaded = entry.produced_row;
      }
      Eigen::VectorXd t(bands), p(bands);
      bool valid = true;
      for (int b = 0; b < bands && valid; ++b) {
        const float v = produced_line(b, entry.produced_col);
        valid = validValue(v, ignore);
        p(b) = v;
        t(b) = spectra[entry.slot * bands + b];
      }
      if (!valid || !(t.norm() > 0.0) || !(p.norm() > 0.0)) continue;
      // 2 asin(|p^ - t^| / 2): the angle, well conditioned near 0 (acos is not).
      const double chord = (p.normalized() - t.normalized()).norm();
      result.sum_deg += 2.0 * std::asin(std::min(1.0, 0.5 * chord)) * 180.0 / std::numbers::pi;
      ++result.pixels;
    }
  }
  return result;
}

}  // namespace

void OrthoMetricsOptions::validate() const {
  const auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("OrthoMetricsOptions: ") + what);
  };
  require(std::isfinite(patch_size_m) && patch_size_m > 0.0, "patch_size_m must be finite and > 0");
  require(min_patch_pixels >= 4, "min_patch_pixels must be >= 4");
  require(min_valid_fraction > 0.0 && min_valid_fraction <= 1.0, "min_valid_fraction must be in (0, 1]");
  require(min_response >= 0.0 && min_response <= 1.0, "min_response must be in [0, 1]");
  require(max_refinements >= 0, "max_refinements must be >= 0");
  require(std::isfinite(confirmation_tolerance_m) && confirmation_tolerance_m > 0.0,
          "confirmation_tolerance_m must be finite and > 0");
  require(std::isfinite(refinement_tolerance_px) && refinement_tolerance_px > 0.0,
          "refinement_tolerance_px must be finite and > 0");
  require(coarse_max_side >= 8, "coarse_max_side must be >= 8");
  require(coarse_min_response >= 0.0 && coarse_min_response <= 1.0,
          "coarse_min_response must be in [0, 1]");
  require(min_matched_fraction >= 0.0 && min_matched_fraction <= 1.0,
          "min_matched_fraction must be in [0, 1]");
  require(min_matched_patches >= 3, "min_matched_patches must be >= 3 (a similarity has 4 unknowns)");
  require(max_sam_pixels > 0, "max_sam_pixels must be > 0");
  require(sam_chunk_bytes > 0, "sam_chunk_bytes must be > 0");
  require(std::isfinite(reference_down_m), "reference_down_m must be finite");
  require(std::isfinite(correlation_cutoff_m) && correlation_cutoff_m >= 0.0,
          "correlation_cutoff_m must be finite and >= 0");
  coarse_similarity.validate();
}

std::string OrthoMetrics::summary() const {
  std::ostringstream out;
  out << "ortho: " << patches << " patches of " << patch_pixels << " px, " << patches_with_data
      << " with data, " << patches_matched << " matched";
  if (patches_unconfirmed > 0) out << " (" << patches_unconfirmed << " more not confirmed)";
  if (coarse_scale && coarse_rotation_deg) {
    out << "; coarse similarity: scale " << *coarse_scale << ", rotation " << *coarse_rotation_deg
        << " deg (" << coarse_feature_inliers << " of " << coarse_feature_matches << " feature matches)";
  }
  if (coarse_shift_NE) {
    out << "; coarse shift (north, east) = (" << coarse_shift_NE->x() << ", " << coarse_shift_NE->y()
        << ") m";
  }
  out << "\n";
  out << "  ortho_mean_shift_m         " << formatFigure(ortho_mean_shift_m) << "\n";
  out << "  ortho_registration_rmse_m  " << formatFigure(ortho_registration_rmse_m) << "\n";
  out << "  ortho_scale_error          " << formatFigure(ortho_scale_error);
  if (rotation_deg) out << "  (rotation " << *rotation_deg << " deg)";
  out << "\n";
  out << "  ortho_sam_deg              " << formatFigure(ortho_sam_deg) << "  (" << sam_pixels
      << " pixels, stride " << sam_stride << (sam_registered ? ", at the registered position" : ", as placed")
      << ")\n";
  out << "  ortho_coverage             " << formatFigure(ortho_coverage) << "  (" << covered_pixels
      << " of " << footprint_pixels << " footprint pixels";
  if (coverage_registered) {
    out << ", registered; as placed " << covered_pixels_as_placed;
  } else {
    out << ", as placed";
  }
  out << ")\n";
  return out.str();
}

OrthoMetrics measureOrtho(const std::filesystem::path& produced_hdr,
                          const std::filesystem::path& truth_hdr, const GeodeticPoint& origin,
                          const OrthoMetricsOptions& options) {
  options.validate();
  const UtmProjection utm(origin);
  const EnviReader truth_reader(truth_hdr);
  const EnviReader produced_reader(produced_hdr);
  const RasterGrid truth = localRasterGrid(truth_reader.header(), truth_reader.headerPath());
  const RasterGrid produced = utmRasterGrid(produced_reader.header(), produced_reader.headerPath(), utm);
  const std::optional<float> ignore =
      enviDataIgnoreValue(produced_reader.header(), produced_reader.headerPath());

  OrthoMetrics metrics;
  const cv::Mat truth_mean = bandMeanImage(truth_reader, std::nullopt);
  const cv::Mat produced_mean = bandMeanImage(produced_reader, ignore);
  const ProducedLookup as_placed(truth, produced, utm, options.reference_down_m);

  // Coverage (nearest produced pixel, as placed) and the bilinear
  // resampling for the coarse shift, in one sweep.
  cv::Mat produced_on_truth(truth.rows, truth.cols, CV_32F);
  for (int r = 0; r < truth.rows; ++r) {
    const float* truth_row = truth_mean.ptr<float>(r);
    float* out = produced_on_truth.ptr<float>(r);
    for (int c = 0; c < truth.cols; ++c) {
      const Eigen::Vector2d at = as_placed.at(r, c);
      out[c] = static_cast<float>(sampleBilinear(produced_mean, at));
      if (std::isnan(truth_row[c])) continue;
      ++metrics.footprint_pixels;
      const auto pixel = nearestPixel(at, produced.rows, produced.cols);
      if (pixel && !std::isnan(produced_mean.at<float>(pixel->first, pixel->second))) {
        ++metrics.covered_pixels;
      }
    }
  }
  metrics.ortho_coverage =
      metrics.footprint_pixels > 0
          ? MetricValue::of(static_cast<double>(metrics.covered_pixels) / metrics.footprint_pixels)
          : MetricValue::missing("truth/reflectance has no valid pixel: the footprint is empty");

  // Registration. The coarse stage (header comment, step 2): the patches
  // look the produced image up through the coarse similarity S0 (W's
  // (east, north): a -> A_W a + b_W; the identity without one) and start
  // from the residual whole-image shift start_px.
  Eigen::Vector2d start_px = Eigen::Vector2d::Zero();  // (d_row, d_col)
  Eigen::Matrix2d A_W = Eigen::Matrix2d::Identity();
  Eigen::Vector2d b_W = Eigen::Vector2d::Zero();
  Eigen::Matrix2d warp_rc = Eigen::Matrix2d::Identity();  // S0's linear part on (row, col) pixels
  std::optional<ProducedLookup> warped;
  std::optional<CoarseSimilarity> coarse_similarity;
  if (options.use_coarse_similarity) {
    coarse_similarity = estimateCoarseSimilarity(truth_mean, produced_on_truth, options.coarse_similarity);
  }
  bool coarse_found = false;
  if (coarse_similarity) {
    // From truth pixels (column, row), p -> A p + b, to W: a = G p + g.
    const Eigen::Matrix2d G = Eigen::Vector2d(truth.px, -truth.py).asDiagonal();
    const Eigen::Vector2d g = truth.centre(0, 0);
    A_W = G * coarse_similarity->A * G.inverse();
    b_W = G * coarse_similarity->b + g - A_W * g;
    warp_rc << coarse_similarity->A(1, 1), coarse_similarity->A(1, 0), coarse_similarity->A(0, 1),
        coarse_similarity->A(0, 0);
    warped.emplace(truth, produced, utm, options.reference_down_m, A_W, b_W);
    cv::Mat produced_warped(truth.rows, truth.cols, CV_32F);
    tbb::parallel_for(0, truth.rows, [&](int r) {
      float* out = produced_warped.ptr<float>(r);
      for (int c = 0; c < truth.cols; ++c) out[c] = static_cast<float>(sampleBilinear(produced_mean, warped->at(r, c)));
    });
    if (const auto residual = coarseShift(truth_mean, produced_warped, options)) start_px = *residual;
    metrics.coarse_scale = coarse_similarity->scale();
    metrics.coarse_rotation_deg = std::atan2(A_W(1, 0), A_W(0, 0)) * 180.0 / std::numbers::pi;
    metrics.coarse_feature_matches = coarse_similarity->matches;
    metrics.coarse_feature_inliers = coarse_similarity->inliers;
    coarse_found = true;
  } else if (const auto coarse = coarseShift(truth_mean, produced_on_truth, options)) {
    start_px = *coarse;
    coarse_found = true;
  }
  const ProducedLookup& patch_lookup = warped ? *warped : as_placed;
  // W (east, north) where the content at a lies in the produced map, given
  // the displacement (d_row, d_col) its patch measured on the warped image.
  const auto producedPosition = [&](const Eigen::Vector2d& a_EN, const Eigen::Vector2d& d_px) {
    return Eigen::Vector2d(A_W * (a_EN + Eigen::Vector2d(d_px.y() * truth.px, -d_px.x() * truth.py)) + b_W);
  };
  if (coarse_found) {
    const Eigen::Vector2d middle = truth.centre(0.5 * (truth.rows - 1), 0.5 * (truth.cols - 1));
    const Eigen::Vector2d shift_EN = producedPosition(middle, start_px) - middle;
    metrics.coarse_shift_NE = Eigen::Vector2d(shift_EN.y(), shift_EN.x());
  }
  const int side = std::max(options.min_patch_pixels,
                            static_cast<int>(std::lround(options.patch_size_m / truth.px)));
  metrics.patch_pixels = side;
  const int patch_rows = truth.rows / side, patch_cols = truth.cols / side;
  metrics.patches = patch_rows * patch_cols;
  const int top = (truth.rows - patch_rows * side) / 2, left = (truth.cols - patch_cols * side) / 2;
  std::vector<PatchResult> results(static_cast<std::size_t>(metrics.patches));
  if (metrics.patches > 0) {
    cv::Mat hann;
    cv::createHanningWindow(hann, cv::Size(side, side), CV_64F);
    tbb::parallel_for(tbb::blocked_range<int>(0, metrics.patches), [&](const tbb::blocked_range<int>& range) {
      for (int k = range.begin(); k != range.end(); ++k) {
        const int r0 = top + (k / patch_cols) * side, c0 = left + (k % patch_cols) * side;
        results[static_cast<std::size_t>(k)] = measurePatch(truth_mean, produced_mean, patch_lookup, hann,
                                                            r0, c0, side, start_px, truth.px, options);
      }
    });
  }
  if (options.confirm_matches && metrics.patches > 0) {
    const double tolerance_px = std::max(2.0, options.confirmation_tolerance_m / truth.px);
    cv::Mat hann;
    cv::createHanningWindow(hann, cv::Size(side, side), CV_64F);
    std::vector<char> confirmed(results.size(), 1);
    tbb::parallel_for(tbb::blocked_range<int>(0, metrics.patches), [&](const tbb::blocked_range<int>& range) {
      for (int k = range.begin(); k != range.end(); ++k) {
        const PatchResult& first = results[static_cast<std::size_t>(k)];
        if (!first.matched) continue;
        const int r0 = top + (k / patch_cols) * side, c0 = left + (k % patch_cols) * side;
        confirmed[static_cast<std::size_t>(k)] =
            confirmMatch(first, truth_mean, produced_mean, patch_lookup, hann, r0, c0, side, start_px,
                         truth.px, tolerance_px, warp_rc, options);
      }
    });
    for (std::size_t k = 0; k < results.size(); ++k) {
      if (results[k].matched && !confirmed[k]) {
        results[k].matched = false;
        ++metrics.patches_unconfirmed;
      }
    }
  }
  std::vector<Eigen::Vector2d> centres_EN, moved_EN;
  for (int k = 0; k < metrics.patches; ++k) {
    const PatchResult& result = results[static_cast<std::size_t>(k)];
    metrics.patches_with_data += result.has_data ? 1 : 0;
    if (!result.matched) continue;
    const int r0 = top + (k / patch_cols) * side, c0 = left + (k % patch_cols) * side;
    const Eigen::Vector2d centre_EN = truth.centre(r0 + 0.5 * (side - 1), c0 + 0.5 * (side - 1));
    const Eigen::Vector2d moved = producedPosition(centre_EN, result.displacement_px);
    const Eigen::Vector2d d_EN = moved - centre_EN;
    centres_EN.push_back(centre_EN);
    moved_EN.push_back(moved);
    OrthoPatchMatch match;
    match.centre_NE = Eigen::Vector2d(centre_EN.y(), centre_EN.x());
    match.displacement_NE = Eigen::Vector2d(d_EN.y(), d_EN.x());
    match.response = result.response;
    metrics.matches.push_back(match);
  }
  metrics.patches_matched = static_cast<int>(metrics.matches.size());

  std::optional<Similarity2d> similarity;
  const double needed = std::max<double>(options.min_matched_patches,
                                         options.min_matched_fraction * metrics.patches_with_data);
  if (metrics.patches_with_data == 0) {
    const std::string why = "no registration patch has data: the produced ortho-image does not overlap "
                            "the true one (" + std::to_string(metrics.patches) + " patches of " +
                            std::to_string(side) + " px)";
    metrics.ortho_mean_shift_m = metrics.ortho_registration_rmse_m = metrics.ortho_scale_error =
        MetricValue::missing(why);
  } else if (metrics.patches_matched < needed) {
    std::ostringstream why;
    why << "too few patches match: " << metrics.patches_matched << " of " << metrics.patches_with_data
        << " with data (phase-correlation response >= " << options.min_response
        << (options.confirm_matches ? ", confirmed on a shifted window" : "") << "), need "
        << static_cast<int>(std::ceil(needed)) << " (" << 100.0 * options.min_matched_fraction
        << " % of those with data and at least "
        << options.min_matched_patches << ")";
    metrics.ortho_mean_shift_m = metrics.ortho_registration_rmse_m = metrics.ortho_scale_error =
        MetricValue::missing(why.str());
  } else {
    Eigen::Vector2d mean_d = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < centres_EN.size(); ++i) mean_d += moved_EN[i] - centres_EN[i];
    mean_d /= static_cast<double>(centres_EN.size());
    metrics.ortho_mean_shift_m = MetricValue::of(mean_d.norm());
    similarity = fitSimilarity(centres_EN, moved_EN);
    if (similarity) {
      double sum2 = 0;
      for (std::size_t i = 0; i < centres_EN.size(); ++i) {
        sum2 += (moved_EN[i] - (similarity->M * centres_EN[i] + similarity->t)).squaredNorm();
      }
      metrics.ortho_registration_rmse_m = MetricValue::of(std::sqrt(sum2 / centres_EN.size()));
      metrics.ortho_scale_error = MetricValue::of(std::abs(similarity->scale() - 1.0));
      metrics.rotation_deg = similarity->rotationDeg();
    } else {
      metrics.ortho_registration_rmse_m = metrics.ortho_scale_error =
          MetricValue::missing("the matched patches share one centre: no similarity");
    }
  }

  // Coverage at the registered position when the registration was
  // measured: what the product covers, apart from where the INS placed it
  // (ortho_mean_shift_m reports that).
  if (similarity) {
    const ProducedLookup registered(truth, produced, utm, options.reference_down_m, similarity->M,
                                    similarity->t);
    std::int64_t covered = 0;
    for (int r = 0; r < truth.rows; ++r) {
      const float* truth_row = truth_mean.ptr<float>(r);
      for (int c = 0; c < truth.cols; ++c) {
        if (std::isnan(truth_row[c])) continue;
        const auto pixel = nearestPixel(registered.at(r, c), produced.rows, produced.cols);
        if (pixel && !std::isnan(produced_mean.at<float>(pixel->first, pixel->second))) ++covered;
      }
    }
    metrics.covered_pixels_as_placed = metrics.covered_pixels;
    metrics.covered_pixels = covered;
    metrics.coverage_registered = true;
    metrics.ortho_coverage = MetricValue::of(static_cast<double>(covered) / metrics.footprint_pixels);
  }

  // Spectral angle.
  if (truth_reader.bands() != produced_reader.bands()) {
    metrics.ortho_sam_deg = MetricValue::missing(
        "the produced ortho-image has " + std::to_string(produced_reader.bands()) +
        " bands, the truth " + std::to_string(truth_reader.bands()) + ": spectra not comparable");
  } else {
    metrics.sam_stride = footprintStride(truth.rows, truth.cols, options.max_sam_pixels);
    metrics.sam_registered = similarity.has_value();
    const ProducedLookup lookup =
        similarity ? ProducedLookup(truth, produced, utm, options.reference_down_m, similarity->M, similarity->t)
                   : as_placed;
    const SamResult sam = spectralAngle(truth_reader, produced_reader, ignore, lookup, metrics.sam_stride,
                                        options.sam_chunk_bytes);
    metrics.sam_pixels = sam.pixels;
    metrics.ortho_sam_deg =
        sam.pixels > 0 ? MetricValue::of(sam.sum_deg / sam.pixels)
                       : MetricValue::missing("no covered pixel with a full, non-zero spectrum in both");
  }
  return metrics;
}

OrthoMetrics measureRunOrtho(const std::filesystem::path& produced_hdr,
                             const std::filesystem::path& truth_hdr, const GeodeticPoint& origin,
                             const OrthoMetricsOptions& options) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(produced_hdr, error)) {
    OrthoMetrics metrics;
    metrics.ortho_mean_shift_m = metrics.ortho_registration_rmse_m = metrics.ortho_scale_error =
        metrics.ortho_sam_deg = metrics.ortho_coverage = MetricValue::missing(kNoOrthoImage);
    return metrics;
  }
  if (!std::filesystem::is_regular_file(truth_hdr, error)) {
    throw InputError(truth_hdr, "",
                     "missing: expected the true reflectance ortho-image (ENVI, "
                     "docs/SURVEY_FORMAT.md) to measure " +
                         produced_hdr.string() + " against");
  }
  return measureOrtho(produced_hdr, truth_hdr, origin, options);
}

}  // namespace hsmap
