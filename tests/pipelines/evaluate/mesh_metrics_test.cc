// mesh_accuracy_m and mesh_completeness through evaluateRun, on hand-made
// meshes against the fixture's flat true seabed (evaluation_fixture.h): every
// figure is one the test can work out from the geometry.
#include "pipelines/evaluate/mesh_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/geometry/sim3.h"
#include "pipelines/evaluate/evaluate_run.h"
#include "tests/pipelines/evaluate/evaluation_fixture.h"

namespace hsmap {
namespace {

using testing::EvaluationFixture;
using testing::flatSeabed;
using testing::kSeabedDown;
using testing::trueSeabed;

double value(const MetricValue& metric) {
  EXPECT_TRUE(metric.value.has_value()) << metric.reason;
  return metric.value.value_or(NAN);
}

PlyMesh shiftedDown(PlyMesh mesh, double down_m) {
  for (Eigen::Vector3d& v : mesh.vertices) v.z() += down_m;
  return mesh;
}

class MeshMetricsTest : public ::testing::Test {
 protected:
  EvaluationMetrics evaluate() const {
    return evaluateRun(loadEvaluationInputs(fixture_.run(), fixture_.truth()));
  }
  EvaluationFixture fixture_;
};

TEST_F(MeshMetricsTest, ACopyOfTheTruthScoresAccuracyZeroAndCompletenessOne) {
  fixture_.writeRunEqualToTruth();
  fixture_.writeRunMesh(trueSeabed());
  const EvaluationMetrics metrics = evaluate();
  EXPECT_NEAR(value(metrics.mesh_accuracy_m), 0.0, 1e-12);
  EXPECT_EQ(value(metrics.mesh_completeness), 1.0);
}

TEST_F(MeshMetricsTest, TheTruthOneCentimetreLowerScoresAccuracyOneCentimetre) {
  fixture_.writeRunEqualToTruth();
  // Finer cells than the truth's: the vertices are not the truth's vertices.
  fixture_.writeRunMesh(flatSeabed(-1.0, 3.0, -1.5, 1.5, 0.1, kSeabedDown + 0.01));
  const EvaluationMetrics metrics = evaluate();
  EXPECT_NEAR(value(metrics.mesh_accuracy_m), 0.01, 1e-12);
  // Every true-surface sample is 1 cm from the mesh: within 2 cm.
  EXPECT_EQ(value(metrics.mesh_completeness), 1.0);
}

TEST_F(MeshMetricsTest, ASurfaceThreeCentimetresOffCoversNothing) {
  fixture_.writeRunEqualToTruth();
  fixture_.writeRunMesh(shiftedDown(trueSeabed(), -0.03));
  const EvaluationMetrics metrics = evaluate();
  EXPECT_NEAR(value(metrics.mesh_accuracy_m), 0.03, 1e-12);
  EXPECT_EQ(value(metrics.mesh_completeness), 0.0);
}

TEST_F(MeshMetricsTest, AMeshOverHalfTheFootprintScoresCompletenessOneHalf) {
  fixture_.writeRunEqualToTruth();
  // The true seabed north of 1.5 m: the northern half of the footprint's
  // north [0.5, 2.5]. Samples are pixel centres 2.5 - (r + 0.5) 0.01; those
  // within 2 cm of the mesh's edge also count: rows 0 to 101 of 200.
  fixture_.writeRunMesh(flatSeabed(1.5, 3.0, -1.5, 1.5, 0.25, kSeabedDown));
  const EvaluationMetrics metrics = evaluate();
  EXPECT_NEAR(value(metrics.mesh_completeness), 0.5, 0.011);
  EXPECT_NEAR(value(metrics.mesh_completeness), 102.0 / 200.0, 1e-12);
  // What there is lies on the truth.
  EXPECT_NEAR(value(metrics.mesh_accuracy_m), 0.0, 1e-12);
}

TEST_F(MeshMetricsTest, TheMeshIsJudgedAfterTheFramesAlignment) {
  // The run's W is the truth's seen through S_est_true: 5 % larger, turned
  // 20 degrees, moved. A mesh consistent with its trajectory scores 0.
  const Sim3 S_est_true(
      1.05, Eigen::Quaterniond(Eigen::AngleAxisd(0.349, Eigen::Vector3d(1, 2, 3).normalized())),
      Eigen::Vector3d(2.0, -1.0, 0.5));
  std::vector<TimedPose> frames = fixture_.framesTrue();
  for (TimedPose& pose : frames) pose.T = S_est_true.transformPose(pose.T);
  std::vector<LinePose> lines = fixture_.linesTrue();
  for (LinePose& pose : lines) pose.T = S_est_true.transformPose(pose.T);
  fixture_.writeRun(frames, lines, fixture_.calibrationEqualToTruth());
  PlyMesh mesh = trueSeabed();
  for (Eigen::Vector3d& v : mesh.vertices) v = S_est_true.apply(v);
  fixture_.writeRunMesh(mesh);
  EvaluationMetrics metrics = evaluate();
  EXPECT_NEAR(value(metrics.mesh_accuracy_m), 0.0, 1e-9);
  EXPECT_EQ(value(metrics.mesh_completeness), 1.0);
  // The attitude-anchored alignment (the frames' orientations turned by the
  // same rotation) maps it back as well.
  EXPECT_NEAR(value(metrics.mesh_accuracy_attitude_aligned_m), 0.0, 1e-9);
  EXPECT_EQ(value(metrics.mesh_completeness_attitude_aligned), 1.0);

  // The same trajectory with the truth's mesh: the mesh disagrees with its
  // own trajectory, and the alignment shows it.
  fixture_.writeRunMesh(trueSeabed());
  metrics = evaluate();
  EXPECT_GT(value(metrics.mesh_accuracy_m), 0.1);
  EXPECT_LT(value(metrics.mesh_completeness), 0.5);
}

TEST_F(MeshMetricsTest, WithoutMeshPlyBothAreNullAndSayWhy) {
  fixture_.writeRunEqualToTruth();
  const EvaluationMetrics metrics = evaluate();
  for (const MetricValue* metric :
       {&metrics.mesh_accuracy_m, &metrics.mesh_completeness,
        &metrics.mesh_accuracy_attitude_aligned_m, &metrics.mesh_completeness_attitude_aligned}) {
    EXPECT_FALSE(metric->value.has_value());
    EXPECT_EQ(metric->reason, "RUN/map/mesh.ply not found: the run has no surface stage");
  }
}

TEST_F(MeshMetricsTest, WithoutTheFramePositionsAlignmentItsPairIsNullAndSaysWhy) {
  // Frames on one line: the positions' similarity is undetermined.
  std::vector<TimedPose> frames = fixture_.framesTrue();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    frames[i].T.t = Eigen::Vector3d(0.01 * static_cast<double>(i), 0.0, 20.0);
  }
  fixture_.writeRun(frames, fixture_.linesTrue(), fixture_.calibrationEqualToTruth());
  fixture_.writeRunMesh(trueSeabed());
  const EvaluationMetrics metrics = evaluate();
  for (const MetricValue* metric :
       {&metrics.mesh_accuracy_positions_aligned_m, &metrics.mesh_completeness_positions_aligned}) {
    EXPECT_FALSE(metric->value.has_value());
    EXPECT_NE(metric->reason.find("no similarity alignment"), std::string::npos) << metric->reason;
  }
  // The view Sim(3) (the contract's) and the attitude-anchored alignment
  // take their rotation from the orientations too (here the truth's): the
  // view points leave the line, so the mesh is measured under both.
  for (const MetricValue* metric :
       {&metrics.mesh_accuracy_m, &metrics.mesh_completeness, &metrics.mesh_accuracy_attitude_aligned_m,
        &metrics.mesh_completeness_attitude_aligned}) {
    EXPECT_TRUE(metric->value.has_value()) << metric->reason;
  }
}

TEST_F(MeshMetricsTest, APointCloudHasAnAccuracyButNoCompleteness) {
  fixture_.writeRunEqualToTruth();
  PlyMesh cloud = shiftedDown(trueSeabed(), 0.004);
  cloud.triangles.clear();
  fixture_.writeRunMesh(cloud);
  const EvaluationMetrics metrics = evaluate();
  EXPECT_NEAR(value(metrics.mesh_accuracy_m), 0.004, 1e-12);
  EXPECT_FALSE(metrics.mesh_completeness.value.has_value());
  EXPECT_NE(metrics.mesh_completeness.reason.find("no triangles"), std::string::npos);
}

TEST_F(MeshMetricsTest, TheAccuracyIsTheMedianOverVertices) {
  // Three vertices of four on the truth, one 1 m off: the median ignores it.
  PlyMesh mesh;
  mesh.vertices = {{1.0, 0.0, kSeabedDown}, {1.1, 0.0, kSeabedDown}, {1.0, 0.1, kSeabedDown},
                   {1.0, 0.0, kSeabedDown - 1.0}};
  mesh.triangles = {{0, 1, 2}};
  fixture_.writeRunEqualToTruth();
  fixture_.writeRunMesh(mesh);
  const EvaluationMetrics metrics = evaluate();
  EXPECT_NEAR(value(metrics.mesh_accuracy_m), 0.0, 1e-12);
  // A 5 cm triangle covers a sliver of the footprint, but some of it.
  EXPECT_GT(value(metrics.mesh_completeness), 0.0);
  EXPECT_LT(value(metrics.mesh_completeness), 0.01);
}

TEST_F(MeshMetricsTest, MetricsJsonCarriesTheValues) {
  fixture_.writeRunEqualToTruth();
  fixture_.writeRunMesh(trueSeabed());
  const EvaluationReport report = evaluateRunFolder(fixture_.run(), fixture_.truth());
  std::ifstream in(report.metrics_path);
  std::stringstream json;
  json << in.rdbuf();
  EXPECT_NE(json.str().find("\"mesh_completeness\": 1,"), std::string::npos) << json.str();
  EXPECT_EQ(json.str().find("\"mesh_accuracy_m\": null"), std::string::npos) << json.str();
  EXPECT_NE(json.str().find("\"mesh_completeness_attitude_aligned\": 1,"), std::string::npos)
      << json.str();
  EXPECT_NE(json.str().find("\"mesh_completeness_positions_aligned\": 1\n"), std::string::npos)
      << json.str();
  EXPECT_NE(json.str().find("\"mesh_accuracy_attitude_aligned_m\": "), std::string::npos);
  EXPECT_EQ(json.str().find("\"mesh_accuracy_attitude_aligned_m\": null"), std::string::npos);
  // The fixture's track wanders 0.4 m sideways: far from weakly conditioned.
  EXPECT_NE(json.str().find("\"alignment_cross_track_spread_m\": 0."), std::string::npos);
}

TEST(MeshMetricsOptionsTest, ValidateRefusesNonsense) {
  MeshMetricsOptions options;
  EXPECT_NO_THROW(options.validate());
  options.completeness_distance_m = 0.0;
  EXPECT_THROW(options.validate(), std::invalid_argument);
  options = MeshMetricsOptions();
  options.max_footprint_samples = 0;
  EXPECT_THROW(options.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
