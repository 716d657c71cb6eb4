#include "core/geometry/pushbroom_camera.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/core/geometry/numeric_jacobian.h"

namespace hsmap {
namespace {

using test::numericJacobian;

PushbroomParameters typicalParameters() {
  PushbroomParameters p;
  p.samples = 1920;
  p.f = 1500.0;
  p.cx = 958.7;
  p.distortion = {0.05, -0.01};
  return p;
}

std::vector<Eigen::Vector3d> randomPoints(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> depth(0.5, 6.0), x(-0.6, 0.6), y(-0.05, 0.05);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) {
    const double z = depth(rng);
    points.emplace_back(x(rng) * z, y(rng) * z, z);
  }
  return points;
}

TEST(PushbroomCamera, ProjectsAHandComputedPoint) {
  PushbroomParameters p;
  p.samples = 1920;
  p.f = 1000.0;
  p.cx = 960.0;
  p.distortion = {0.1, 0.01};
  const PushbroomCamera camera(p);
  // x = 0.25: x_d = 0.25 (1 + 0.1 * 0.0625 + 0.01 * 0.00390625) = 0.251572265625.
  const Eigen::Vector2d projection = camera.project(Eigen::Vector3d(0.5, 0.2, 2.0));
  EXPECT_DOUBLE_EQ(projection.x(), 1211.572265625);
  EXPECT_DOUBLE_EQ(projection.y(), 0.1);
  // On the optical axis: the principal point, on the line.
  EXPECT_EQ(camera.project(Eigen::Vector3d(0.0, 0.0, 3.0)), Eigen::Vector2d(960.0, 0.0));
}

TEST(PushbroomCamera, UnprojectInvertsProjectOnTheScanPlane) {
  const PushbroomCamera camera(typicalParameters());
  for (const auto& p : randomPoints(200, 1)) {
    const Eigen::Vector3d on_line(p.x(), 0.0, p.z());
    const std::optional<Eigen::Vector3d> ray = camera.unproject(camera.project(on_line).x());
    ASSERT_TRUE(ray.has_value()) << p.transpose();
    EXPECT_EQ(ray->y(), 0.0);
    EXPECT_NEAR(ray->norm(), 1.0, 1e-15);
    EXPECT_LT((*ray - on_line.normalized()).norm(), 1e-13) << p.transpose();
  }
  for (double u : {-0.5, 0.0, 958.7, 1500.25, 1919.49}) {
    const std::optional<Eigen::Vector3d> ray = camera.unproject(u);
    ASSERT_TRUE(ray.has_value()) << u;
    EXPECT_NEAR(camera.project(*ray).x(), u, 1e-9);
    EXPECT_EQ(camera.project(*ray).y(), 0.0);
  }
}

TEST(PushbroomCamera, MonotonicRegionEndsAtTheFirstRootOfTheDerivative) {
  PushbroomParameters p = typicalParameters();
  // k2 = 0, k1 = -0.3: g'(x) = 1 - 0.9 x^2 vanishes at x = 1/sqrt(0.9), where
  // g = x (1 - 0.3 / 0.9) = (2/3) / sqrt(0.9).
  p.distortion = {-0.3, 0.0};
  const PushbroomCamera barrel(p);
  const double x_max = 1.0 / std::sqrt(0.9);
  EXPECT_NEAR(barrel.maxMonotonicTangent(), x_max, 1e-15);
  const double g_max = (2.0 / 3.0) * x_max;
  EXPECT_FALSE(barrel.unproject(p.cx + p.f * (g_max + 1e-6)).has_value());
  EXPECT_FALSE(barrel.unproject(p.cx - p.f * (g_max + 1e-6)).has_value());
  const std::optional<Eigen::Vector3d> near_fold = barrel.unproject(p.cx - p.f * (g_max - 1e-6));
  ASSERT_TRUE(near_fold.has_value());
  EXPECT_LT(std::abs(near_fold->x() / near_fold->z()), x_max);
  EXPECT_NEAR(barrel.project(*near_fold).x(), p.cx - p.f * (g_max - 1e-6), 1e-7);

  // k1 = 0, k2 = -0.1: g'(x) = 1 - 0.5 x^4 vanishes at x = 2^(1/4).
  p.distortion = {0.0, -0.1};
  EXPECT_NEAR(PushbroomCamera(p).maxMonotonicTangent(), std::pow(2.0, 0.25), 1e-15);
  // Both non-zero: 1 + 3 k1 s + 5 k2 s^2 with k1 = 0.2, k2 = -0.05 has its
  // positive root at s = (0.6 + sqrt(0.36 + 1)) / 0.5.
  p.distortion = {0.2, -0.05};
  EXPECT_NEAR(PushbroomCamera(p).maxMonotonicTangent(),
              std::sqrt((0.6 + std::sqrt(1.36)) / 0.5), 1e-14);
  // Pincushion (k1, k2 >= 0) never folds, and a large offset still inverts.
  p.distortion = {0.3, 0.1};
  const PushbroomCamera pincushion(p);
  EXPECT_TRUE(std::isinf(pincushion.maxMonotonicTangent()));
  const Eigen::Vector3d far_ray = *pincushion.unproject(p.cx + p.f * 40.0);
  EXPECT_NEAR(pincushion.project(far_ray).x(), p.cx + p.f * 40.0, 1e-7);
}

TEST(PushbroomCamera, AnalyticJacobiansMatchNumericDifferentiation) {
  const PushbroomCamera camera(typicalParameters());
  for (const auto& p : randomPoints(20, 2)) {
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
          return PushbroomCamera::projectWith(intrinsics.data(), p);
        },
        Eigen::Map<const Eigen::VectorXd>(k.data(), k.size()), 1e-3);
    EXPECT_LT((camera.projectJacobianIntrinsics(p) - numeric_intrinsics).norm(),
              1e-9 * numeric_intrinsics.norm())
        << p.transpose();
  }
}

TEST(PushbroomCamera, AutodiffEqualsAnalyticJacobians) {
  using Jet = ceres::Jet<double, 7>;  // 3 point coordinates + 4 intrinsics
  const PushbroomCamera camera(typicalParameters());
  for (const auto& p : randomPoints(20, 3)) {
    Vector3<Jet> p_jet;
    for (int i = 0; i < 3; ++i) p_jet(i) = Jet(p(i), i);
    std::array<Jet, 4> intrinsics;
    for (int i = 0; i < 4; ++i) intrinsics[i] = Jet(camera.intrinsics()[i], 3 + i);
    const Vector2<Jet> projection = PushbroomCamera::projectWith(intrinsics.data(), p_jet);
    Eigen::Matrix<double, 2, 7> autodiff;
    autodiff.row(0) = projection.x().v.transpose();
    autodiff.row(1) = projection.y().v.transpose();
    Eigen::Matrix<double, 2, 7> analytic;
    analytic << camera.projectJacobianPoint(p), camera.projectJacobianIntrinsics(p);
    EXPECT_LT((autodiff - analytic).norm(), 1e-12 * analytic.norm()) << p.transpose();
  }
}

TEST(PushbroomCamera, LineCoversHalfAPixelAroundTheCentres) {
  const PushbroomCamera camera(typicalParameters());
  EXPECT_TRUE(camera.isInLine(-0.5));
  EXPECT_TRUE(camera.isInLine(1919.49));
  EXPECT_FALSE(camera.isInLine(1919.5));
  EXPECT_FALSE(camera.isInLine(-0.500001));
}

TEST(PushbroomCamera, RejectsInvalidParameters) {
  PushbroomParameters p = typicalParameters();
  p.samples = 0;
  try {
    PushbroomCamera camera(p);
    FAIL() << "zero samples were accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()), "PushbroomCamera: samples must be positive, got 0");
  }
  p = typicalParameters();
  p.f = 0.0;
  EXPECT_THROW(PushbroomCamera{p}, std::invalid_argument);
  p = typicalParameters();
  p.distortion[1] = INFINITY;
  EXPECT_THROW(PushbroomCamera{p}, std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
