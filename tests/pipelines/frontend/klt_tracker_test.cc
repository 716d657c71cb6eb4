#include "pipelines/frontend/klt_tracker.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <algorithm>
#include <cmath>
#include <random>

#include "pipelines/frontend/corner_detector.h"

namespace hsmap {
namespace {

// A blurred random texture, and the same texture shifted by (dx, dy).
cv::Mat texture(int width, int height, double dx, double dy) {
  cv::Mat noise(height + 80, width + 80, CV_8U);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, dx - 40.0, 0, 1, dy - 40.0);
  cv::Mat out;
  cv::warpAffine(noise, out, shift, cv::Size(width, height), cv::INTER_LINEAR);
  return out;
}

TEST(KltTracker, FollowsAShiftAndFlagsPointsThatLeftTheImage) {
  const FrontendOptions options;
  const KltTracker tracker(options, 640);
  const cv::Mat a = texture(640, 480, 0.0, 0.0), b = texture(640, 480, 6.5, -4.25);
  const GridCornerDetector detector(options, 640, 480);
  std::vector<cv::Point2f> points = detector.detect(a, {});
  ASSERT_GT(points.size(), 100u);
  points.emplace_back(637.0f, 240.0f);  // moves out of the image
  std::vector<cv::Point2f> tracked;
  const std::vector<bool> good = tracker.track(tracker.buildPyramid(a), tracker.buildPyramid(b), points, points, tracked);
  std::vector<double> errors;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if (!good[i]) continue;
    errors.push_back(std::hypot(tracked[i].x - points[i].x - 6.5, tracked[i].y - points[i].y + 4.25));
  }
  EXPECT_GT(errors.size(), std::size_t(0.9 * double(points.size())));
  // The interpolated shift blurs the second image a little: most points
  // within a twentieth of a pixel, nearly all within a quarter.
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.05);
  EXPECT_LT(errors[errors.size() * 95 / 100], 0.25);
  EXPECT_FALSE(good.back());
}

TEST(KltTracker, ForwardBackwardCheckRejectsAPointOnAChangedPatch) {
  const FrontendOptions options;
  const KltTracker tracker(options, 640);
  const cv::Mat a = texture(640, 480, 0.0, 0.0);
  cv::Mat b = texture(640, 480, 3.0, 2.0);
  // Something covers the centre of the second image.
  cv::Mat cover(b.size(), CV_8U);
  cv::RNG(99).fill(cover, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(cover, cover, cv::Size(0, 0), 2.0);
  cover(cv::Rect(270, 190, 100, 100)).copyTo(b(cv::Rect(270, 190, 100, 100)));
  const std::vector<cv::Point2f> points{{320.0f, 240.0f}, {100.0f, 100.0f}};
  std::vector<cv::Point2f> tracked;
  const std::vector<bool> good = tracker.track(tracker.buildPyramid(a), tracker.buildPyramid(b), points, points, tracked);
  EXPECT_FALSE(good[0]);
  EXPECT_TRUE(good[1]);
}

TEST(GridCornerDetector, CoversTheGridAndLeavesRoomAroundExistingTracks) {
  const FrontendOptions options;
  const GridCornerDetector detector(options, 640, 480);
  const cv::Mat image = texture(640, 480, 0.0, 0.0);
  const std::vector<cv::Point2f> corners = detector.detect(image, {});
  EXPECT_GT(detector.coverage(corners), 0.9);
  // No cell gets more than its share.
  std::vector<int> per_cell(std::size_t(detector.cellsAcross() * detector.cellsDown()), 0);
  for (const auto& p : corners) ++per_cell[std::size_t(detector.cellOf(p))];
  EXPECT_LE(*std::max_element(per_cell.begin(), per_cell.end()), options.max_corners_per_cell);
  // With those as existing tracks, only the empty room is filled.
  const std::vector<cv::Point2f> more = detector.detect(image, corners);
  EXPECT_LT(more.size(), corners.size() / 4);
  for (const auto& p : more) {
    for (const auto& q : corners) EXPECT_GT(cv::norm(p - q), options.min_corner_distance_px * 640 / 960 - 1.0);
  }
}

TEST(GridCornerDetector, FindsNothingInABlackImage) {
  const GridCornerDetector detector(FrontendOptions{}, 640, 480);
  EXPECT_TRUE(detector.detect(cv::Mat::zeros(480, 640, CV_8U), {}).empty());
}

}  // namespace
}  // namespace hsmap
