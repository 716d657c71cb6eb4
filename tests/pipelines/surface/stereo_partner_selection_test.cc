// selectStereoPartners picks, for each keyframe, the neighbour seeing the
// same landmarks at the baseline ratio sought, and the depth range to search.
#include "pipelines/surface/stereo_partner_selection.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <stdexcept>

namespace hsmap {
namespace {

// Keyframes every `spacing` metres along x at `altitude` above a seabed
// (z = 0, z down so cameras at z = -altitude) looking down, each observing
// the landmarks of a grid under its field of view.
VisualMap downwardTrack(int count, double spacing, double altitude) {
  VisualMap map;
  SE3d T_W_C;
  T_W_C.q = Eigen::Quaterniond(Eigen::AngleAxisd(0.0, Eigen::Vector3d::UnitZ()));  // z forward = down
  for (int k = 0; k < count; ++k) {
    T_W_C.t = Eigen::Vector3d(spacing * k, 0.0, -altitude);
    map.addKeyframe(k, 0.1 * k, 0, T_W_C);
  }
  const double half_width = 0.6 * altitude;
  for (double x = -half_width; x <= spacing * (count - 1) + half_width; x += 0.1) {
    for (double y = -half_width; y <= half_width; y += 0.1) {
      const int l = map.addLandmark(0, Eigen::Vector3d(x, y, 0.0));
      for (int k = 0; k < count; ++k) {
        if (std::abs(x - spacing * k) <= half_width) map.addObservation(k, l, Eigen::Vector2d(0, 0));
      }
    }
  }
  return map;
}

TEST(StereoPartnerSelection, PicksTheNeighbourAtTheTargetBaselineRatio) {
  const VisualMap map = downwardTrack(20, 0.1, 2.0);
  StereoPartnerOptions options;  // target B / Z = 0.2: 0.4 m, four keyframes away
  const auto partners = selectStereoPartners(map, options);
  ASSERT_EQ(partners.size(), 20u);
  for (int k = 0; k < 20; ++k) {
    ASSERT_TRUE(partners[std::size_t(k)]) << k;
    const StereoPartner& p = *partners[std::size_t(k)];
    EXPECT_EQ(p.keyframe, k);
    EXPECT_EQ(std::abs(p.partner - k), 4) << k;
    EXPECT_NEAR(p.baseline_m, 0.4, 1e-9);
    EXPECT_NEAR(p.median_depth_m, 2.0, 1e-9);
    EXPECT_NEAR(p.min_depth_m, 2.0 * (1 - options.depth_margin), 1e-9);
    EXPECT_NEAR(p.max_depth_m, 2.0 * (1 + options.depth_margin), 1e-9);
  }
}

TEST(StereoPartnerSelection, NoPartnerWhenEveryNeighbourIsTooClose) {
  const VisualMap map = downwardTrack(5, 0.02, 2.0);  // at most 0.08 m apart: B / Z <= 0.04
  for (const auto& partner : selectStereoPartners(map, StereoPartnerOptions{})) {
    EXPECT_FALSE(partner);
  }
}

TEST(StereoPartnerSelection, NoPartnerThatLooksElsewhere) {
  VisualMap map = downwardTrack(6, 0.1, 2.0);
  // Keyframe 4 turned 30 degrees away: keyframe 0 must not pick it.
  map.keyframe(4).T_F_C.q = Eigen::Quaterniond(Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitX()));
  const auto partners = selectStereoPartners(map, StereoPartnerOptions{});
  ASSERT_TRUE(partners[0]);
  EXPECT_NE(partners[0]->partner, 4);
}

TEST(StereoPartnerSelection, InvalidOptionsAreNamed) {
  StereoPartnerOptions options;
  EXPECT_EQ(options.validate(), "");
  options.min_baseline_ratio = 0.3;
  EXPECT_EQ(options.validate(), "stereo baseline ratios must satisfy 0 < min <= target <= max");
  options = {};
  options.max_axis_angle_deg = 90.0;
  EXPECT_EQ(options.validate(), "max_axis_angle_deg must be in (0, 90)");
  options = {};
  options.min_landmarks = 2;
  EXPECT_EQ(options.validate(), "min_landmarks must be at least 3");
  EXPECT_THROW(selectStereoPartners(VisualMap{}, options), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
