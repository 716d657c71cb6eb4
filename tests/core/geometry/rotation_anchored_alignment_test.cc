#include "core/geometry/rotation_anchored_alignment.h"

#include <gtest/gtest.h>

#include <random>

#include "core/geometry/so3.h"

namespace hsmap {
namespace {

TEST(ChordalMeanRotation, IsTheRotationBetweenSymmetricPerturbations) {
  const Eigen::Quaterniond centre(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()));
  std::vector<Eigen::Quaterniond> rotations;
  for (const Eigen::Vector3d axis : {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()}) {
    rotations.push_back(centre * Eigen::Quaterniond(Eigen::AngleAxisd(0.1, axis)));
    rotations.push_back(centre * Eigen::Quaterniond(Eigen::AngleAxisd(-0.1, axis)));
  }
  const Eigen::Quaterniond mean = chordalMeanRotation(rotations);
  EXPECT_LT(logSO3(Eigen::Quaterniond(mean.conjugate() * centre)).norm(), 1e-12);
  EXPECT_THROW(chordalMeanRotation({}), std::invalid_argument);
}

TEST(AlignScaleTranslation, RecoversScaleAndTranslationOfCollinearPointsGivenTheRotation) {
  // Collinear points: a point fit cannot find the roll about the line, but
  // with the rotation given, scale and translation are determined.
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.4, Eigen::Vector3d(0, 1, 1).normalized()));
  const Sim3 truth(2.5, q, Eigen::Vector3d(1, 2, 3));
  std::vector<Eigen::Vector3d> source, target;
  for (int i = 0; i < 10; ++i) {
    source.emplace_back(0.3 * i, 0.0, 0.0);
    target.push_back(truth.apply(source.back()));
  }
  const Sim3 fit = alignScaleTranslation(q, source, target);
  EXPECT_NEAR(fit.scale(), 2.5, 1e-12);
  EXPECT_TRUE(fit.translation().isApprox(truth.translation(), 1e-12));
  try {
    alignScaleTranslation(q, {source[0], source[0]}, {target[0], target[1]});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "alignScaleTranslation: the points do not move along each other; no positive "
                 "scale fits");
  }
}

}  // namespace
}  // namespace hsmap
