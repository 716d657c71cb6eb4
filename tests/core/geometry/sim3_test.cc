// Sim3: the group operations against 4x4 matrices, camera poses, and the
// Umeyama alignments (exact, noisy, degenerate, rigid, with gross outliers).

#include "core/geometry/sim3.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/geometry/so3.h"

namespace hsmap {
namespace {

Sim3 knownSim3() {
  return Sim3(2.5, expSO3(Eigen::Vector3d(0.3, -1.1, 0.7)), Eigen::Vector3d(10.0, -4.0, 2.5));
}

// Points spread over a 10 m box (a survey-sized cloud), in frame A.
std::vector<Eigen::Vector3d> randomPoints(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> uniform(-5.0, 5.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) points.emplace_back(uniform(rng), uniform(rng), uniform(rng));
  return points;
}

std::vector<Eigen::Vector3d> applyAll(const Sim3& S_B_A, const std::vector<Eigen::Vector3d>& p_A) {
  std::vector<Eigen::Vector3d> p_B;
  for (const Eigen::Vector3d& p : p_A) p_B.push_back(S_B_A.apply(p));
  return p_B;
}

double rotationError(const Sim3& a, const Sim3& b) {
  return a.rotation().angularDistance(b.rotation());
}

std::string alignmentError(const std::vector<Eigen::Vector3d>& source,
                           const std::vector<Eigen::Vector3d>& target) {
  try {
    alignUmeyama(source, target);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(Sim3, ApplyComposeAndInverseAgreeWithMatrices) {
  const Sim3 S_B_A = knownSim3();
  const Sim3 S_C_B(0.4, expSO3(Eigen::Vector3d(-2.0, 0.1, 0.5)), Eigen::Vector3d(-1.0, 3.0, 0.2));
  const Eigen::Vector3d p_A(0.3, -2.0, 5.0);
  const Eigen::Matrix3d R = S_B_A.rotation().toRotationMatrix();
  EXPECT_LT((S_B_A.apply(p_A) - (2.5 * R * p_A + S_B_A.translation())).norm(), 1e-13);
  EXPECT_LT((S_B_A.apply(p_A) - (S_B_A.matrix() * p_A.homogeneous()).head<3>()).norm(), 1e-13);
  EXPECT_LT(((S_C_B * S_B_A).matrix() - S_C_B.matrix() * S_B_A.matrix()).norm(), 1e-13);
  EXPECT_LT((S_B_A.inverse().matrix() - S_B_A.matrix().inverse()).norm(), 1e-13);
  EXPECT_NEAR(S_B_A.inverse().scale(), 0.4, 1e-15);
  EXPECT_LT(((S_B_A * S_B_A.inverse()).matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-13);
  EXPECT_EQ(Sim3::identity().apply(p_A), p_A);
}

TEST(Sim3, TransformPoseMovesTheCentreAndTurnsTheAxesButDoesNotScaleThem) {
  const Sim3 S_B_A = knownSim3();
  const SE3d T_A_C(expSO3(Eigen::Vector3d(0.2, 0.4, -0.3)), Eigen::Vector3d(1.0, 2.0, 3.0));
  const SE3d T_B_C = S_B_A.transformPose(T_A_C);
  // Rotation R R_A_C, translation s R t_A_C + t: the centre maps like a point.
  EXPECT_LT(T_B_C.q.angularDistance(S_B_A.rotation() * T_A_C.q), 1e-15);
  EXPECT_LT((T_B_C.t - S_B_A.apply(T_A_C.t)).norm(), 1e-13);
  EXPECT_NEAR(T_B_C.q.norm(), 1.0, 1e-15);
  // A point of the camera frame: S_B_A (T_A_C p_C) = T_B_C (s p_C).
  const Eigen::Vector3d p_C(0.5, -0.2, 4.0);
  EXPECT_LT((S_B_A.apply(T_A_C * p_C) - T_B_C * Eigen::Vector3d(2.5 * p_C)).norm(), 1e-12);
}

TEST(Sim3, RejectsANonPositiveOrNonFiniteScale) {
  EXPECT_THROW(Sim3(0.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(Sim3(-1.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(Sim3(NAN, Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(Sim3(1.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.0, INFINITY, 0.0)),
               std::invalid_argument);
}

TEST(Sim3, AlignUmeyamaRecoversAKnownSim3FromNoiselessPoints) {
  std::mt19937 rng(3);
  const Sim3 truth = knownSim3();
  const std::vector<Eigen::Vector3d> source = randomPoints(rng, 20);
  const Sim3 estimate = alignUmeyama(source, applyAll(truth, source));
  EXPECT_NEAR(estimate.scale(), truth.scale(), 1e-9);
  EXPECT_LT(rotationError(estimate, truth), 1e-9);
  EXPECT_LT((estimate.translation() - truth.translation()).norm(), 1e-9);
  // The minimum of 3 pairs is enough.
  const std::vector<Eigen::Vector3d> three(source.begin(), source.begin() + 3);
  const Sim3 minimal = alignUmeyama(three, applyAll(truth, three));
  EXPECT_LT((minimal.matrix() - truth.matrix()).norm(), 1e-9);
}

TEST(Sim3, AlignUmeyamaAcceptsAPlanarSource) {
  // A flat seabed: every source point at the same depth.
  std::mt19937 rng(5);
  std::vector<Eigen::Vector3d> source = randomPoints(rng, 15);
  for (Eigen::Vector3d& p : source) p.z() = 20.0;
  const Sim3 truth = knownSim3();
  const Sim3 estimate = alignUmeyama(source, applyAll(truth, source));
  EXPECT_LT((estimate.matrix() - truth.matrix()).norm(), 1e-9);
}

TEST(Sim3, AlignUmeyamaRecoversASim3WithinTheNoise) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Sim3 truth = knownSim3();
  const std::vector<Eigen::Vector3d> source = randomPoints(rng, 200);
  std::vector<Eigen::Vector3d> target = applyAll(truth, source);
  const double sigma = 0.02;  // metres, per axis
  for (Eigen::Vector3d& p : target) p += sigma * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  const Sim3 estimate = alignUmeyama(source, target);
  // 200 points over a ~25 m (scaled) box: the errors of the fit are far below
  // sigma; these bounds are several times what the noise gives.
  EXPECT_NEAR(estimate.scale(), truth.scale(), 1e-3);
  EXPECT_LT(rotationError(estimate, truth), 5e-4);
  EXPECT_LT((estimate.translation() - truth.translation()).norm(), 1e-2);
  EXPECT_GT((estimate.translation() - truth.translation()).norm(), 0.0);
}

TEST(Sim3, AlignUmeyamaWithoutScaleFixesItToOne) {
  std::mt19937 rng(9);
  const Sim3 rigid(1.0, expSO3(Eigen::Vector3d(0.1, 0.2, -0.4)), Eigen::Vector3d(1.0, 2.0, 3.0));
  const std::vector<Eigen::Vector3d> source = randomPoints(rng, 10);
  const Sim3 estimate = alignUmeyama(source, applyAll(rigid, source), false);
  EXPECT_EQ(estimate.scale(), 1.0);
  EXPECT_LT((estimate.matrix() - rigid.matrix()).norm(), 1e-9);
  // Data that is scaled keeps a scale of 1 (the best rigid fit).
  const Sim3 scaled = alignUmeyama(source, applyAll(knownSim3(), source), false);
  EXPECT_EQ(scaled.scale(), 1.0);
  EXPECT_NE(alignUmeyama(source, applyAll(knownSim3(), source), true).scale(), 1.0);
}

TEST(Sim3, AlignUmeyamaRejectsDegenerateInputsSayingWhy) {
  std::mt19937 rng(11);
  const std::vector<Eigen::Vector3d> source = randomPoints(rng, 5);
  const std::vector<Eigen::Vector3d> target = applyAll(knownSim3(), source);

  EXPECT_EQ(alignmentError(source, std::vector<Eigen::Vector3d>(target.begin(), target.end() - 1)),
            "alignUmeyama: source and target must pair up, got 5 source and 4 target points");
  EXPECT_EQ(alignmentError({source[0], source[1]}, {target[0], target[1]}),
            "alignUmeyama: at least 3 point pairs are needed, got 2");

  const std::vector<Eigen::Vector3d> equal(5, Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(alignmentError(equal, target),
            "alignUmeyama: the source points all coincide, so the alignment is undetermined "
            "(degenerate)");

  std::vector<Eigen::Vector3d> collinear;
  for (int i = 0; i < 5; ++i) collinear.push_back(Eigen::Vector3d(1, 2, 3) + 0.7 * i * Eigen::Vector3d(1, -1, 2));
  EXPECT_EQ(alignmentError(collinear, target),
            "alignUmeyama: the source points are collinear, so the rotation about their line is "
            "undetermined (degenerate); they must span at least a plane");
  // Far from the origin, rounding of the coordinates must not hide it.
  for (Eigen::Vector3d& p : collinear) p += Eigen::Vector3d(6.6e6, 5.9e5, 20.0);
  EXPECT_NE(alignmentError(collinear, target).find("collinear"), std::string::npos);

  // A collapsed target cannot carry a rotation either.
  EXPECT_NE(alignmentError(source, equal).find("the target points all coincide"), std::string::npos);

  std::vector<Eigen::Vector3d> with_nan = source;
  with_nan[2].y() = NAN;
  EXPECT_EQ(alignmentError(with_nan, target), "alignUmeyama: point pair 2 is not finite");
}

struct OutlierScene {
  Sim3 truth = knownSim3();
  std::vector<Eigen::Vector3d> source;
  std::vector<Eigen::Vector3d> target;
  std::vector<bool> outlier;
};

// n pairs with 1 cm noise; every fifth (20 %) displaced by 1-5 m.
OutlierScene makeOutlierScene(unsigned seed, int n, const Sim3& truth = knownSim3()) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> metres(1.0, 5.0);
  OutlierScene scene;
  scene.truth = truth;
  scene.source = randomPoints(rng, n);
  scene.target = applyAll(scene.truth, scene.source);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d& p = scene.target[i];
    p += 0.01 * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    scene.outlier.push_back(i % 5 == 2);
    if (scene.outlier.back()) {
      p += metres(rng) * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    }
  }
  return scene;
}

TEST(Sim3, RobustAlignmentSurvivesTwentyPercentGrossOutliersAndFlagsThem) {
  const OutlierScene scene = makeOutlierScene(13, 100);
  const RobustAlignment result = alignUmeyamaRobust(scene.source, scene.target, 0.1);
  ASSERT_EQ(result.inliers.size(), 100u);
  for (std::size_t i = 0; i < scene.outlier.size(); ++i) {
    EXPECT_EQ(result.inliers[i], !scene.outlier[i]) << "pair " << i;
  }
  EXPECT_EQ(result.inlier_count, 80u);
  // 1 cm per axis: a 3-D error of about sqrt(3) cm.
  EXPECT_NEAR(result.inlier_rms, 0.01 * std::sqrt(3.0), 0.005);
  EXPECT_NEAR(result.sim3.scale(), scene.truth.scale(), 1e-3);
  EXPECT_LT(rotationError(result.sim3, scene.truth), 1e-3);
  EXPECT_LT((result.sim3.translation() - scene.truth.translation()).norm(), 1e-2);

  // The plain least-squares fit is dragged away by the same outliers.
  const Sim3 plain = alignUmeyama(scene.source, scene.target);
  EXPECT_GT(rotationError(plain, scene.truth) + std::abs(plain.scale() - scene.truth.scale()) +
                (plain.translation() - scene.truth.translation()).norm(),
            0.05);
}

TEST(Sim3, RobustAlignmentIsDeterministic) {
  const OutlierScene scene = makeOutlierScene(17, 60);
  const RobustAlignment a = alignUmeyamaRobust(scene.source, scene.target, 0.1);
  const RobustAlignment b = alignUmeyamaRobust(scene.source, scene.target, 0.1);
  EXPECT_EQ(a.sim3.matrix(), b.sim3.matrix());
  EXPECT_EQ(a.inliers, b.inliers);
}

TEST(Sim3, RobustAlignmentWithoutScaleIsRigid) {
  const Sim3 rigid(1.0, knownSim3().rotation(), knownSim3().translation());
  const OutlierScene scene = makeOutlierScene(19, 50, rigid);
  const RobustAlignment result = alignUmeyamaRobust(scene.source, scene.target, 0.1, false);
  EXPECT_EQ(result.sim3.scale(), 1.0);
  EXPECT_LT(rotationError(result.sim3, rigid), 1e-3);
  EXPECT_LT((result.sim3.translation() - rigid.translation()).norm(), 1e-2);
  EXPECT_EQ(result.inlier_count, 40u);
}

TEST(Sim3, RobustAlignmentRejectsBadInputsAndReportsNoConsensus) {
  const OutlierScene scene = makeOutlierScene(23, 20);
  EXPECT_THROW(alignUmeyamaRobust(scene.source, scene.target, 0.0), std::invalid_argument);
  EXPECT_THROW(alignUmeyamaRobust(scene.source, scene.target, NAN), std::invalid_argument);
  EXPECT_THROW(alignUmeyamaRobust({scene.source[0], scene.source[1]},
                                  {scene.target[0], scene.target[1]}, 0.1),
               std::invalid_argument);
  const std::vector<Eigen::Vector3d> equal(20, Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_THROW(alignUmeyamaRobust(equal, scene.target, 0.1), std::invalid_argument);
  // Random targets: no 3 pairs agree to within a micrometre.
  std::mt19937 rng(29);
  const std::vector<Eigen::Vector3d> unrelated = randomPoints(rng, 20);
  try {
    alignUmeyamaRobust(scene.source, unrelated, 1e-6);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no alignment is supported by 3 or more pairs"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hsmap
