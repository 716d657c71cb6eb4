#include "pipelines/evaluate/ortho_coarse_similarity.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

namespace hsmap {
namespace {

// An image reduced by `factor` (area averaging) as 8-bit grey for the
// detector, and where features may lie.
struct ReducedImage {
  cv::Mat grey;  // CV_8U
  cv::Mat mask;  // CV_8U, 255 where a feature may lie
};

// `image` cropped to whole blocks of factor x factor pixels and averaged
// over each block; a block with an empty pixel is empty. The valid pixels are
// mapped to 8 bits by their mean +- 3 standard deviations (the detector and
// descriptor are invariant to the remaining affine change of intensity),
// the empty ones set to the mean grey.
ReducedImage reduce(const cv::Mat& image, int factor, int border_px) {
  const cv::Size reduced(image.cols / factor, image.rows / factor);
  const cv::Mat cropped = image(cv::Rect(0, 0, reduced.width * factor, reduced.height * factor));
  cv::Mat valid = (cropped == cropped);  // false at NaN
  cv::Mat filled = cropped.clone();
  filled.setTo(0.0f, ~valid);
  cv::Mat valid_float;
  valid.convertTo(valid_float, CV_32F, 1.0 / 255.0);
  cv::Mat sum, fraction;
  cv::resize(filled, sum, reduced, 0, 0, cv::INTER_AREA);
  cv::resize(valid_float, fraction, reduced, 0, 0, cv::INTER_AREA);
  cv::Mat reduced_valid = fraction > 0.999f;

  ReducedImage out;
  cv::Scalar mean, sd;
  cv::meanStdDev(sum, mean, sd, reduced_valid);
  const double scale = sd[0] > 0.0 ? 128.0 / (3.0 * sd[0]) : 0.0;
  sum.convertTo(out.grey, CV_8U, scale, 128.0 - scale * mean[0]);  // saturating
  out.grey.setTo(128, ~reduced_valid);
  if (border_px > 0) {
    cv::erode(reduced_valid, out.mask,
              cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * border_px + 1, 2 * border_px + 1)),
              cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  } else {
    out.mask = reduced_valid;
  }
  return out;
}

}  // namespace

void CoarseSimilarityOptions::validate() const {
  const auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("CoarseSimilarityOptions: ") + what);
  };
  require(max_side >= 32, "max_side must be >= 32");
  require(max_features >= 0, "max_features must be >= 0 (0: all)");
  require(ratio > 0.0 && ratio <= 1.0, "ratio must be in (0, 1]");
  require(std::isfinite(ransac_threshold_px) && ransac_threshold_px > 0.0,
          "ransac_threshold_px must be finite and > 0");
  require(min_inliers >= 3, "min_inliers must be >= 3");
  require(std::isfinite(max_scale_error) && max_scale_error > 0.0, "max_scale_error must be finite and > 0");
  require(border_px >= 0, "border_px must be >= 0");
}

double CoarseSimilarity::scale() const { return std::hypot(A(0, 0), A(1, 0)); }

double CoarseSimilarity::rotationDeg() const {
  return std::atan2(A(1, 0), A(0, 0)) * 180.0 / std::numbers::pi;
}

std::optional<CoarseSimilarity> estimateCoarseSimilarity(const cv::Mat& truth, const cv::Mat& produced,
                                                         const CoarseSimilarityOptions& options) {
  options.validate();
  if (truth.type() != CV_32F || produced.type() != CV_32F || truth.size() != produced.size()) {
    throw std::invalid_argument("estimateCoarseSimilarity: expected two CV_32F images of the same size");
  }
  const int longest = std::max(truth.rows, truth.cols);
  const int factor = std::max(1, (longest + options.max_side - 1) / options.max_side);
  if (truth.rows / factor < 16 || truth.cols / factor < 16) return std::nullopt;
  const ReducedImage t = reduce(truth, factor, options.border_px);
  const ReducedImage p = reduce(produced, factor, options.border_px);

  const cv::Ptr<cv::SIFT> sift = cv::SIFT::create(options.max_features);
  std::vector<cv::KeyPoint> t_keys, p_keys;
  cv::Mat t_descriptors, p_descriptors;
  sift->detectAndCompute(t.grey, t.mask, t_keys, t_descriptors);
  sift->detectAndCompute(p.grey, p.mask, p_keys, p_descriptors);
  if (static_cast<int>(t_keys.size()) < options.min_inliers ||
      static_cast<int>(p_keys.size()) < options.min_inliers) {
    return std::nullopt;
  }

  const cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> knn;
  matcher.knnMatch(t_descriptors, p_descriptors, knn, 2);
  std::vector<cv::Point2f> from, to;
  for (const auto& pair : knn) {
    if (pair.size() < 2 || !(pair[0].distance < options.ratio * pair[1].distance)) continue;
    from.push_back(t_keys[static_cast<std::size_t>(pair[0].queryIdx)].pt);
    to.push_back(p_keys[static_cast<std::size_t>(pair[0].trainIdx)].pt);
  }
  if (static_cast<int>(from.size()) < options.min_inliers) return std::nullopt;

  std::vector<uchar> inlier_flags;
  const cv::Mat M = cv::estimateAffinePartial2D(from, to, inlier_flags, cv::RANSAC,
                                                options.ransac_threshold_px, 5000, 0.999, 10);
  if (M.empty()) return std::nullopt;
  CoarseSimilarity result;
  result.matches = static_cast<int>(from.size());
  result.inliers = static_cast<int>(std::count(inlier_flags.begin(), inlier_flags.end(), uchar{1}));
  // Reduced pixel centre i is full-resolution (column, row) factor i + c,
  // c = (factor - 1) / 2: q = A p + b in reduced pixels becomes
  // q = A p + factor b + (I - A) c in full-resolution pixels.
  Eigen::Matrix2d A;
  A << M.at<double>(0, 0), M.at<double>(0, 1), M.at<double>(1, 0), M.at<double>(1, 1);
  const Eigen::Vector2d b_reduced(M.at<double>(0, 2), M.at<double>(1, 2));
  const Eigen::Vector2d c = Eigen::Vector2d::Constant(0.5 * (factor - 1));
  result.A = A;
  result.b = factor * b_reduced + (Eigen::Matrix2d::Identity() - A) * c;
  const double s = result.scale();
  if (result.inliers < options.min_inliers || !std::isfinite(s) || s > 1.0 + options.max_scale_error ||
      s < 1.0 / (1.0 + options.max_scale_error)) {
    return std::nullopt;
  }
  return result;
}

}  // namespace hsmap
