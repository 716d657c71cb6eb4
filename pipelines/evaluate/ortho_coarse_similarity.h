#pragma once
// The coarse 2-D similarity between a produced ortho-image and the true one,
// both on the truth's grid (ortho_metrics.h, registration step 2): where the
// registration patches start from, so that each patch's own correlation only
// has a small residual displacement left to find.
//
// Why a similarity and not a translation: a map whose scale is wrong by s
// moves content at a distance r from the scale's centre by (s - 1) r, and
// scales the content inside every patch by s. With an 11 % scale over a
// 4 m swath, patches 2 m from the centre were displaced by ~0.2 m (more
// than a 0.3 m patch's capture range of +-0.15 m) and their 0.3 m of
// content stretched by 3 cm (several times the 4 cm band limit of the patch
// correlation): 6 of 37 patches matched and the metrics were null, where an
// independent evaluator measured 4.9 mm. Warping the produced image by the
// coarse similarity first leaves each patch only the map's local error.
//
// Method: feature matching, SIFT (Lowe, IJCV 2004) on both band-mean images
// reduced by area averaging to at most max_side pixels a side, Lowe's ratio
// test, then cv::estimateAffinePartial2D (4 degrees of freedom: scale,
// rotation, translation) with RANSAC and its least-squares refinement on the
// inliers. Why not log-polar (Fourier-Mellin) phase correlation: it reads
// scale and rotation from the magnitude spectra of the two WHOLE images,
// which are those of the same content only when the two cover the same
// ground. Here they do not: the swath is a long, irregular strip (NaN
// outside), the produced image is cut at the truth's frame, and at 11 % the
// two footprints differ by decimetres; the footprint edges and the shading
// along the strip dominate the low frequencies the log-polar transform
// resolves best. Feature matching is local: features outside the overlap or
// on the edges find no partner or are RANSAC outliers, and the seabed's
// texture (boulders, patches of sediment, speckle) gives hundreds of
// blob-like features, which is what SIFT's difference-of-Gaussians detects,
// at any scale and orientation (ORB's FAST corners are few on blobs).
// SIFT and the RANSAC of OpenCV (fixed seed) are deterministic.
//
// The result is trusted when at least min_inliers matches agree (random
// matches of unrelated images agree by chance with a probability of order
// (pi * threshold^2 / image area)^k; for 10 it is nil), and its scale is
// within [1 / (1 + max_scale_error), 1 + max_scale_error].
#include <optional>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace hsmap {

struct CoarseSimilarityOptions {
  // Longest side of the reduced images. 1024: rugged's 1 cm truth raster
  // (397 x 1964) is read at 2 cm, fine enough for its boulders and sediment
  // patches, coarse enough that the product's and the truth's finest
  // textures (sampled differently) do not decide.
  int max_side = 1024;
  // SIFT keeps the strongest max_features (bounds the matching's cost).
  int max_features = 3000;
  // Lowe's ratio test: best over second-best descriptor distance.
  double ratio = 0.8;
  // RANSAC inlier threshold, in pixels of the reduced images.
  double ransac_threshold_px = 2.0;
  int min_inliers = 10;
  // A scale outside [1 / (1 + this), 1 + this] is not a map's error.
  double max_scale_error = 0.5;
  // Features this close (reduced pixels) to an empty pixel are not used:
  // the footprint's edge is not the same edge in the two images.
  int border_px = 6;

  // std::invalid_argument naming the field when a value is out of range.
  void validate() const;
};

// produced position = A * truth position + b, both (column, row) in pixels
// of the full-resolution truth grid.
struct CoarseSimilarity {
  Eigen::Matrix2d A = Eigen::Matrix2d::Identity();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  int matches = 0;  // feature matches passing the ratio test
  int inliers = 0;  // of those, agreeing with the similarity

  // Scale and rotation (degrees, from the column axis towards the row axis).
  double scale() const;
  double rotationDeg() const;
};

// `truth` and `produced`: CV_32F images of the same size on the truth's grid
// (the produced one resampled as placed), NaN where empty. The similarity
// taking a truth pixel to where its content lies in `produced`, or nullopt
// when it is not trusted (above) or either image has too few features.
// std::invalid_argument for other types or sizes, or bad options.
std::optional<CoarseSimilarity> estimateCoarseSimilarity(const cv::Mat& truth, const cv::Mat& produced,
                                                         const CoarseSimilarityOptions& options = {});

}  // namespace hsmap
