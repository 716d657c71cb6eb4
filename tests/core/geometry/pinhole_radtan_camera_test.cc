#include "core/geometry/pinhole_radtan_camera.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/core/geometry/numeric_jacobian.h"

namespace hsmap {
namespace {

using test::numericJacobian;

PinholeRadtanParameters typicalParameters() {
  PinholeRadtanParameters p;
  p.width = 960;
  p.height = 540;
  p.fx = 800.0;
  p.fy = 790.0;
  p.cx = 481.3;
  p.cy = 268.9;
  p.distortion = {-0.28, 0.09, 0.0012, -0.0008, -0.012};
  return p;
}

// Points in front of the camera whose projections fall inside (and a bit
// beyond) the image.
std::vector<Eigen::Vector3d> randomPointsInView(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> depth(0.5, 8.0), x(-0.65, 0.65), y(-0.38, 0.38);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) {
    const double z = depth(rng);
    points.emplace_back(x(rng) * z, y(rng) * z, z);
  }
  return points;
}

TEST(PinholeRadtanCamera, ProjectionMatchesOpenCv) {
  const PinholeRadtanCamera camera(typicalParameters());
  const auto points = randomPointsInView(200, 1);
  std::vector<cv::Point3d> object;
  for (const auto& p : points) object.emplace_back(p.x(), p.y(), p.z());
  const auto& k = camera.intrinsics();
  const cv::Matx33d K(k[0], 0, k[2], 0, k[1], k[3], 0, 0, 1);
  const std::vector<double> dist(camera.parameters().distortion.begin(),
                                 camera.parameters().distortion.end());
  std::vector<cv::Point2d> expected;
  cv::projectPoints(object, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, dist, expected);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d pixel = camera.project(points[i]);
    EXPECT_NEAR(pixel.x(), expected[i].x, 1e-9) << i;
    EXPECT_NEAR(pixel.y(), expected[i].y, 1e-9) << i;
  }
}

TEST(PinholeRadtanCamera, UnprojectInvertsProject) {
  const PinholeRadtanCamera camera(typicalParameters());
  for (const auto& p : randomPointsInView(200, 2)) {
    const std::optional<Eigen::Vector3d> ray = camera.unproject(camera.project(p));
    ASSERT_TRUE(ray.has_value()) << p.transpose();
    EXPECT_NEAR(ray->norm(), 1.0, 1e-15);
    EXPECT_LT((*ray - p.normalized()).norm(), 1e-12) << p.transpose();
  }
  // Every pixel of the image, corners included, has a ray that projects back.
  for (double u : {-0.5, 0.0, 240.0, 480.0, 959.4}) {
    for (double v : {-0.5, 0.0, 135.0, 539.4}) {
      const std::optional<Eigen::Vector3d> ray = camera.unproject(Eigen::Vector2d(u, v));
      ASSERT_TRUE(ray.has_value()) << u << " " << v;
      EXPECT_LT((camera.project(*ray) - Eigen::Vector2d(u, v)).norm(), 1e-9) << u << " " << v;
    }
  }
}

TEST(PinholeRadtanCamera, UnprojectRejectsPixelsBeyondTheDistortionFold) {
  PinholeRadtanParameters p = typicalParameters();
  // Radial r (1 - 0.5 r^2) peaks at r = sqrt(2/3) with r_d = 0.5443: no ray
  // maps farther out than that.
  p.distortion = {-0.5, 0.0, 0.0, 0.0, 0.0};
  const PinholeRadtanCamera camera(p);
  const double inside = 0.54, beyond = 0.55;
  EXPECT_TRUE(camera.unproject(Eigen::Vector2d(p.cx + p.fx * inside, p.cy)).has_value());
  EXPECT_FALSE(camera.unproject(Eigen::Vector2d(p.cx + p.fx * beyond, p.cy)).has_value());
  EXPECT_FALSE(camera.unproject(Eigen::Vector2d(p.cx, p.cy - p.fy * beyond)).has_value());
  // Inside, the ray found is the inner one (r < sqrt(2/3)), not the one past the fold.
  const Eigen::Vector3d ray = *camera.unproject(Eigen::Vector2d(p.cx + p.fx * inside, p.cy));
  EXPECT_LT(ray.x() / ray.z(), std::sqrt(2.0 / 3.0));
  EXPECT_NEAR(camera.project(ray).x(), p.cx + p.fx * inside, 1e-9);
}

TEST(PinholeRadtanCamera, AnalyticJacobiansMatchNumericDifferentiation) {
  const PinholeRadtanCamera camera(typicalParameters());
  for (const auto& p : randomPointsInView(20, 3)) {
    const Eigen::MatrixXd numeric_point = numericJacobian(
        [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
          return camera.project(Eigen::Vector3d(x));
        },
        p);
    EXPECT_LT((camera.projectJacobianPoint(p) - numeric_point).norm(),
              1e-9 * numeric_point.norm())
        << p.transpose();
    // The projection is linear in each intrinsic on its own, so a central
    // difference is exact but for rounding, which a large step keeps small
    // (eps |u| / h with |u| ~ 1e3).
    const auto& k = camera.intrinsics();
    const Eigen::MatrixXd numeric_intrinsics = numericJacobian(
        [&](const Eigen::VectorXd& intrinsics) -> Eigen::VectorXd {
          return PinholeRadtanCamera::projectWith(intrinsics.data(), p);
        },
        Eigen::Map<const Eigen::VectorXd>(k.data(), k.size()), 1e-3);
    EXPECT_LT((camera.projectJacobianIntrinsics(p) - numeric_intrinsics).norm(),
              1e-9 * numeric_intrinsics.norm())
        << p.transpose();
  }
}

TEST(PinholeRadtanCamera, AutodiffEqualsAnalyticJacobians) {
  using Jet = ceres::Jet<double, 12>;  // 3 point coordinates + 9 intrinsics
  const PinholeRadtanCamera camera(typicalParameters());
  for (const auto& p : randomPointsInView(20, 4)) {
    Vector3<Jet> p_jet;
    for (int i = 0; i < 3; ++i) p_jet(i) = Jet(p(i), i);
    std::array<Jet, 9> intrinsics;
    for (int i = 0; i < 9; ++i) intrinsics[i] = Jet(camera.intrinsics()[i], 3 + i);
    const Vector2<Jet> pixel = PinholeRadtanCamera::projectWith(intrinsics.data(), p_jet);
    Eigen::Matrix<double, 2, 12> autodiff;
    autodiff.row(0) = pixel.x().v.transpose();
    autodiff.row(1) = pixel.y().v.transpose();
    Eigen::Matrix<double, 2, 12> analytic;
    analytic << camera.projectJacobianPoint(p), camera.projectJacobianIntrinsics(p);
    EXPECT_LT((autodiff - analytic).norm(), 1e-12 * analytic.norm()) << p.transpose();
    EXPECT_NEAR(pixel.x().a, camera.project(p).x(), 1e-12);
  }
}

TEST(PinholeRadtanCamera, ImageCoversHalfAPixelAroundTheCentres) {
  const PinholeRadtanCamera camera(typicalParameters());
  EXPECT_TRUE(camera.isInImage({-0.5, -0.5}));
  EXPECT_TRUE(camera.isInImage({959.49, 539.49}));
  EXPECT_FALSE(camera.isInImage({959.5, 10.0}));
  EXPECT_FALSE(camera.isInImage({10.0, 539.5}));
  EXPECT_FALSE(camera.isInImage({-0.51, 10.0}));
}

TEST(PinholeRadtanCamera, RejectsInvalidParameters) {
  PinholeRadtanParameters p = typicalParameters();
  p.fx = -800.0;
  try {
    PinholeRadtanCamera camera(p);
    FAIL() << "a negative fx was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()),
              "PinholeRadtanCamera: fx must be a positive finite number, got -800.000000");
  }
  p = typicalParameters();
  p.width = 0;
  EXPECT_THROW(PinholeRadtanCamera{p}, std::invalid_argument);
  p = typicalParameters();
  p.distortion[4] = std::nan("");
  EXPECT_THROW(PinholeRadtanCamera{p}, std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
