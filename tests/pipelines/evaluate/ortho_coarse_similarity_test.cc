// estimateCoarseSimilarity (ortho_coarse_similarity.h) on synthetic band-mean
// images: a smooth random texture (smooth_texture.h) sampled at 5 mm on a
// long strip with a wavy, NaN edge (the swath), and the same texture under a
// known similarity with its own strip, as a produced image resampled on the
// truth's grid is.
#include "pipelines/evaluate/ortho_coarse_similarity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>
#include <opencv2/core.hpp>

#include "tests/pipelines/evaluate/smooth_texture.h"

namespace hsmap {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr double kPixel = 0.005;
constexpr int kRows = 200, kCols = 600;

const testing::SmoothTexture& texture() {
  static const testing::SmoothTexture t(7, -0.5, -0.5, 1000, 1500);
  return t;
}

// p = (column, row) -> produced (column, row) = A p + b.
struct PixelSimilarity {
  Eigen::Matrix2d A = Eigen::Matrix2d::Identity();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  static PixelSimilarity of(double scale, double rotation_deg, const Eigen::Vector2d& centre,
                            const Eigen::Vector2d& shift) {
    const double th = rotation_deg * std::numbers::pi / 180.0;
    PixelSimilarity S;
    S.A << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
    S.A *= scale;
    S.b = centre - S.A * centre + shift;
    return S;
  }
};

// The strip: rows between two wavy edges, NaN outside.
bool inStrip(double row, double col) {
  const double wave = 12.0 * std::sin(2 * std::numbers::pi * col / 250.0);
  return row > 25.0 + wave && row < kRows - 25.0 + wave;
}

// Pixel (row, col) shows the texture at the truth pixel S^-1 (col, row);
// the strip is the image's own (not mapped), as footprints differ.
cv::Mat image(const PixelSimilarity& S, unsigned strip_seed = 0) {
  const Eigen::Matrix2d A_inv = S.A.inverse();
  cv::Mat out(kRows, kCols, CV_32F);
  for (int r = 0; r < kRows; ++r) {
    for (int c = 0; c < kCols; ++c) {
      if (!inStrip(r + 7.0 * strip_seed, c)) {
        out.at<float>(r, c) = kNaN;
        continue;
      }
      const Eigen::Vector2d p = A_inv * (Eigen::Vector2d(c, r) - S.b);
      out.at<float>(r, c) = static_cast<float>(1.0 + 0.2 * texture()(p.y() * kPixel, p.x() * kPixel));
    }
  }
  return out;
}

void expectSimilarity(const CoarseSimilarity& found, const PixelSimilarity& S) {
  EXPECT_NEAR(found.scale(), S.A.col(0).norm(), 0.005);
  EXPECT_NEAR(found.rotationDeg(), std::atan2(S.A(1, 0), S.A(0, 0)) * 180.0 / std::numbers::pi, 0.2);
  // Where the strip's pixels go, within a pixel.
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(50, 60), Eigen::Vector2d(550, 140), Eigen::Vector2d(300, 100)}) {
    EXPECT_LT((found.A * p + found.b - (S.A * p + S.b)).norm(), 1.0) << p.transpose();
  }
}

TEST(OrthoCoarseSimilarity, FindsAScaleRotationAndShift) {
  const cv::Mat truth = image(PixelSimilarity{});
  for (const double scale : {1.15, 0.87}) {
    SCOPED_TRACE("scale " + std::to_string(scale));
    const PixelSimilarity S = PixelSimilarity::of(scale, -3.0, Eigen::Vector2d(420, 60), Eigen::Vector2d(-14, 9));
    const auto found = estimateCoarseSimilarity(truth, image(S, 1));
    ASSERT_TRUE(found);
    EXPECT_GE(found->inliers, 30);
    expectSimilarity(*found, S);
  }
}

TEST(OrthoCoarseSimilarity, ReducedImagesGiveFullResolutionPixels) {
  // max_side 256: the 600-pixel strip is read at a third of its resolution.
  CoarseSimilarityOptions options;
  options.max_side = 256;
  const PixelSimilarity S = PixelSimilarity::of(1.11, 2.0, Eigen::Vector2d(200, 150), Eigen::Vector2d(25, -6));
  const auto found = estimateCoarseSimilarity(image(PixelSimilarity{}), image(S, 1), options);
  ASSERT_TRUE(found);
  expectSimilarity(*found, S);
}

TEST(OrthoCoarseSimilarity, FeaturelessOrUnrelatedImagesHaveNone) {
  const cv::Mat truth = image(PixelSimilarity{});
  cv::Mat flat(kRows, kCols, CV_32F, cv::Scalar(0.5));
  EXPECT_FALSE(estimateCoarseSimilarity(truth, flat));
  // Another texture entirely.
  const testing::SmoothTexture other(99, -0.5, -0.5, 1000, 1500);
  cv::Mat unrelated(kRows, kCols, CV_32F);
  for (int r = 0; r < kRows; ++r) {
    for (int c = 0; c < kCols; ++c) unrelated.at<float>(r, c) = static_cast<float>(other(r * kPixel, c * kPixel));
  }
  EXPECT_FALSE(estimateCoarseSimilarity(truth, unrelated));
}

TEST(OrthoCoarseSimilarity, RejectsBadInputsAndOptions) {
  const cv::Mat truth = image(PixelSimilarity{});
  EXPECT_THROW(estimateCoarseSimilarity(truth, cv::Mat(kRows, kCols, CV_64F, cv::Scalar(0))), std::invalid_argument);
  EXPECT_THROW(estimateCoarseSimilarity(truth, truth(cv::Rect(0, 0, 100, 100)).clone()), std::invalid_argument);
  CoarseSimilarityOptions options;
  options.min_inliers = 2;
  EXPECT_THROW(estimateCoarseSimilarity(truth, truth, options), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
