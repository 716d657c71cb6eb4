// The complete example of docs/ENGINE.md, compiled and run here so that it
// cannot rot: the code between the markers below must be identical to the
// ```cpp block of docs/ENGINE.md (checked by ExampleInTheDocsIsThisCode).

// [engine-example-begin]
#include <iostream>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"
#include "core/geometry/so3.h"
#include "core/graph/factor_graph.h"
#include "core/graph/values.h"
#include "factors/ins_attitude_factor.h"
#include "factors/ins_position_factor.h"
#include "factors/reprojection_factor.h"
#include "solvers/graph_problem.h"
#include "solvers/graph_solver.h"
#include "solvers/marginal_covariance.h"

using namespace hsmap;

// Three keyframes 0.5 m apart, 3 m above 25 seabed points (W is NED, so the
// camera's z axis, down, is W's z). The measurements are exact here, so the
// solve must land on the truth from its rough start.
SolveReport solveExample(Values& values, Eigen::MatrixXd& covariance_x1) {
  PinholeRadtanParameters intrinsics;
  intrinsics.width = 640;
  intrinsics.height = 480;
  intrinsics.fx = intrinsics.fy = 500.0;
  intrinsics.cx = 319.5;
  intrinsics.cy = 239.5;
  const PinholeRadtanCamera camera(intrinsics);
  const SE3d T_B_C;  // the camera sits at the INS body origin, same axes

  FactorGraph graph;
  const NoiseModel pixel_noise = NoiseModel::isotropic(2, 0.5);           // pixels
  const NoiseModel ins_position_noise = NoiseModel::isotropic(3, 0.05);   // metres
  const NoiseModel ins_attitude_noise = NoiseModel::isotropic(3, 0.002);  // radians
  for (int k = 0; k < 3; ++k) {
    const SE3d T_W_C(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.5 * k, 0.0, 17.0));
    for (int i = 0; i < 25; ++i) {
      const Eigen::Vector3d p_W(0.4 * (i % 5) - 0.3, 0.4 * (i / 5) - 0.8, 20.0 + 0.05 * (i % 3));
      const Eigen::Vector2d pixel = camera.project(Eigen::Vector3d(T_W_C.inverse() * p_W));
      graph.emplace<ReprojectionFactor>(X(k), L(i), pixel, intrinsics, pixel_noise,
                                        RobustLoss::huber(2.0));
      if (k == 0) values.insertPoint(L(i), p_W + Eigen::Vector3d(0.05, -0.03, 0.1));
    }
    // The INS measures the body pose T_W_B = T_W_C * T_B_C^-1.
    graph.emplace<InsPositionFactor>(X(k), T_W_C.t, T_B_C, ins_position_noise);
    graph.emplace<InsAttitudeFactor>(X(k), T_W_C.q, T_B_C, ins_attitude_noise);
    values.insertPose(X(k), T_W_C.q * expSO3(Eigen::Vector3d(0.02, -0.01, 0.03)),
                      T_W_C.t + Eigen::Vector3d(0.1, 0.1, -0.1));
  }

  // The INS factors fix the gauge, so nothing needs to be held constant.
  GraphProblem problem(graph, values);
  SolverOptions options;  // Levenberg-Marquardt, SPARSE_SCHUR, every hardware thread
  const SolveReport report = solve(problem, options);
  std::cout << report.toString() << "\n";

  // 6x6 covariance of keyframe 1 over its right perturbation [rho; phi].
  covariance_x1 = marginalCovariances(problem, {X(1)}).at(X(1));
  return report;
}
// [engine-example-end]

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(EngineExample, SolvesToTheTruthAndGivesAPoseCovariance) {
  Values values;
  Eigen::MatrixXd covariance;
  const SolveReport report = solveExample(values, covariance);
  EXPECT_TRUE(report.converged) << report.toString();
  EXPECT_EQ(report.linear_solver, "SPARSE_SCHUR (SuiteSparse)");
  EXPECT_EQ(report.by_factor_type.at("ReprojectionFactor").count, 75u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT((values.poseTranslation(X(k)) - Eigen::Vector3d(0.5 * k, 0.0, 17.0)).norm(), 1e-6);
    EXPECT_LT(values.poseRotation(X(k)).angularDistance(Eigen::Quaterniond::Identity()), 1e-7);
  }
  EXPECT_LT((values.point(L(7)) - Eigen::Vector3d(0.5, -0.4, 20.05)).norm(), 1e-6);
  ASSERT_EQ(covariance.rows(), 6);
  EXPECT_LT((covariance - covariance.transpose()).norm(), 1e-12 * covariance.norm());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(covariance);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0);
  // Vision ties the three keyframes together, so keyframe 1 is known better
  // than by its own INS fix alone.
  EXPECT_LT((covariance.topLeftCorner<3, 3>().trace()), 3 * 0.05 * 0.05);
}

TEST(EngineExample, ExampleInTheDocsIsThisCode) {
  const std::filesystem::path here(__FILE__);
  const std::string source = readFile(here);
  const std::string begin_marker = "// [engine-example-begin]\n";
  const std::string end_marker = "// [engine-example-end]\n";
  const std::size_t begin = source.find(begin_marker);
  const std::size_t end = source.find(end_marker);
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  const std::string example = source.substr(begin + begin_marker.size(), end - begin - begin_marker.size());

  const std::filesystem::path doc_path = here.parent_path() / ".." / ".." / "docs" / "ENGINE.md";
  const std::string doc = readFile(doc_path);
  ASSERT_FALSE(doc.empty()) << "cannot read " << doc_path;
  const std::size_t block = doc.find("```cpp\n");
  ASSERT_NE(block, std::string::npos) << "no ```cpp block in " << doc_path;
  const std::size_t block_end = doc.find("```\n", block + 7);
  ASSERT_NE(block_end, std::string::npos);
  EXPECT_EQ(doc.substr(block + 7, block_end - block - 7), example)
      << "docs/ENGINE.md's example differs from tests/solvers/engine_example_test.cc";
}

}  // namespace
