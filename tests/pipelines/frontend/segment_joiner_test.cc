// Joining map segments by vision (segment_joiner.h): two keyframes of the
// same seabed give the similarity between their segments; two keyframes of
// unrelated seabed give no verified join.
#include "pipelines/frontend/segment_joiner.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>
#include <string>

#include "tests/pipelines/frontend/synthetic_scene.h"

namespace hsmap {
namespace {

constexpr double kFocal = 400.0;

// A pinhole camera without distortion, 480x360, and a blobby random texture
// (the seabed) seen from a camera looking straight down at a plane 1 m away:
// moving the camera by dx along x shifts the image by -kFocal dx pixels.
PinholeRadtanCamera flatCamera() {
  PinholeRadtanParameters p;
  p.width = 480;
  p.height = 360;
  p.fx = p.fy = kFocal;
  p.cx = 239.5;
  p.cy = 179.5;
  p.distortion = {0.0, 0.0, 0.0, 0.0, 0.0};
  return PinholeRadtanCamera(p);
}

cv::Mat seabedTexture(unsigned seed) {
  cv::Mat noise(600, 800, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  cv::Mat blurred;
  cv::GaussianBlur(noise, blurred, cv::Size(0, 0), 2.5);
  cv::Mat image;
  cv::normalize(blurred, image, 0, 255, cv::NORM_MINMAX, CV_8U);
  return image;
}

// The camera's image of the texture with the camera at x = dx (metres).
cv::Mat viewOf(const cv::Mat& texture, double dx, const PinholeRadtanCamera& camera) {
  const int x0 = 100 + int(std::lround(kFocal * dx)), y0 = 100;
  return texture(cv::Rect(x0, y0, camera.width(), camera.height())).clone();
}

// A keyframe at x = dx over the plane z = 1 of G, with `count` landmarks at
// random pixels, expressed in frame X = S_X_G(G).
JoinKeyframeView keyframeView(int id, double dx, const Sim3& S_X_G, cv::Mat gray, const PinholeRadtanCamera& camera,
                              unsigned seed) {
  JoinKeyframeView view;
  view.keyframe_id = id;
  view.segment = id;
  view.T_X_C = S_X_G.transformPose(SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(dx, 0.0, 0.0)));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(30.0, 450.0), v(30.0, 330.0);
  for (int i = 0; i < 150; ++i) {
    // A landmark on the plane, seen at an integer-ish pixel of the earlier view.
    const double x = std::round(u(rng)), y = std::round(v(rng));
    const Eigen::Vector3d p_G((x - camera.parameters().cx) / kFocal + dx, (y - camera.parameters().cy) / kFocal, 1.0);
    view.landmark_ids.push_back(1000 * id + i);
    view.p_X.push_back(S_X_G.apply(p_G));
    view.pixels.emplace_back(x, y);
  }
  view.gray = std::move(gray);
  return view;
}

SegmentJoinOptions options(const std::string& descriptor = "sift") {
  SegmentJoinOptions o;
  o.descriptor = descriptor;
  o.pnp.min_inliers = o.min_inliers;
  o.pnp.ransac_iterations = 500;
  return o;
}

// Both descriptors (SIFT, the default, and ORB) join the same seabed and
// refuse an unrelated one.
class SegmentJoinerWith : public ::testing::TestWithParam<std::string> {};

// Two described keyframes of the same seabed across a gap: the camera moved
// 6 cm (24 px), and the new keyframe's segment S is a similarity S_S_G away
// from G; the new keyframe sees the same landmarks.
struct SameSeabedPair {
  PinholeRadtanCamera camera = flatCamera();
  Sim3 S_S_G{2.5, expSO3(Eigen::Vector3d(0.2, -0.1, 0.4)), Eigen::Vector3d(1.0, 2.0, -0.5)};
  JoinKeyframeView earlier, later;
  explicit SameSeabedPair(const std::string& descriptor) {
    const cv::Mat texture = seabedTexture(1);
    const double dx = 0.06;
    earlier = keyframeView(0, 0.0, Sim3(), viewOf(texture, 0.0, camera), camera, 7);
    later = keyframeView(1, dx, S_S_G, viewOf(texture, dx, camera), camera, 7);
    for (std::size_t i = 0; i < later.pixels.size(); ++i) later.pixels[i].x() -= kFocal * dx;
    // The same landmarks, seen from the new pose: positions in S are S_S_G of G's.
    for (std::size_t i = 0; i < later.p_X.size(); ++i) later.p_X[i] = S_S_G.apply(earlier.p_X[i]);
    describeJoinView(earlier, options(descriptor));
    describeJoinView(later, options(descriptor));
  }
};

TEST_P(SegmentJoinerWith, TwoKeyframesOfTheSameSeabedGiveTheSimilarityBetweenTheirSegments) {
  const SameSeabedPair pair(GetParam());
  const auto& [camera, S_S_G, earlier, later] = pair;
  EXPECT_EQ(earlier.descriptors.type(), GetParam() == "sift" ? CV_32F : CV_8U);
  const SegmentJoin join = joinKeyframePair(earlier, later, camera, options(GetParam()));
  ASSERT_TRUE(join.ok) << join.failure;
  EXPECT_GE(join.inliers, 100);
  EXPECT_NEAR(join.S_G_S.scale(), 1.0 / 2.5, 1e-3);
  EXPECT_LT(testing::rotationAngleDeg(join.S_G_S.rotation(), S_S_G.inverse().rotation()), 0.05);
  EXPECT_LT(join.reprojection_rms_px, 0.5);
  for (const auto& [e, n] : join.landmark_pairs) EXPECT_EQ(e % 1000, n % 1000);  // the same landmark
}

TEST_P(SegmentJoinerWith, TwoKeyframesOfUnrelatedSeabedGiveNoJoin) {
  const PinholeRadtanCamera camera = flatCamera();
  JoinKeyframeView earlier = keyframeView(0, 0.0, Sim3(), viewOf(seabedTexture(1), 0.0, camera), camera, 7);
  // Another seabed, and landmarks elsewhere: nothing in common but chance.
  JoinKeyframeView later = keyframeView(1, 0.06, Sim3(), viewOf(seabedTexture(2), 0.06, camera), camera, 8);
  describeJoinView(earlier, options(GetParam()));
  describeJoinView(later, options(GetParam()));
  const SegmentJoin join = joinKeyframePair(earlier, later, camera, options(GetParam()));
  EXPECT_FALSE(join.ok) << join.matches << " matches, " << join.inliers << " inliers";
  EXPECT_FALSE(join.failure.empty());
  std::cout << "refused: " << join.failure << "\n";
}

// Guided matching under an accepted similarity pairs each landmark with
// itself, also where the descriptors alone would be ambiguous, and pairs
// nothing under a similarity that is wrong by more than the gates.
TEST_P(SegmentJoinerWith, UnderTheAcceptedSimilarityEveryLandmarkPairsWithItself) {
  const SameSeabedPair pair(GetParam());
  const auto& [camera, S_S_G, earlier, later] = pair;
  const double threshold_G = 0.05;  // 5 % of the 1 m altitude
  const auto pairs = pairsUnderSimilarity(earlier, later, camera, S_S_G.inverse(), threshold_G, options(GetParam()));
  EXPECT_GE(pairs.size(), std::size_t(earlier.descriptors.rows) * 9 / 10);
  for (const auto& [e, n] : pairs) EXPECT_EQ(e % 1000, n % 1000);
  // 2 cm of translation off at 1 m is 8 px in both views: beyond the 3 px
  // gate, where only another landmark that happens to fall within it can
  // pair (150 landmarks in the image: a few percent of them).
  const Sim3 wrong = Sim3(1.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.02, 0.0, 0.0)) * S_S_G.inverse();
  const auto chance = pairsUnderSimilarity(earlier, later, camera, wrong, threshold_G, options(GetParam()));
  EXPECT_LE(chance.size(), std::size_t(earlier.descriptors.rows) / 20);
  for (const auto& [e, n] : chance) EXPECT_NE(e % 1000, n % 1000);
}

INSTANTIATE_TEST_SUITE_P(Descriptors, SegmentJoinerWith, ::testing::Values("sift", "orb"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(SegmentJoiner, AnUnknownDescriptorIsRefused) {
  const PinholeRadtanCamera camera = flatCamera();
  JoinKeyframeView view = keyframeView(0, 0.0, Sim3(), viewOf(seabedTexture(1), 0.0, camera), camera, 7);
  EXPECT_THROW(describeJoinView(view, options("akaze")), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
