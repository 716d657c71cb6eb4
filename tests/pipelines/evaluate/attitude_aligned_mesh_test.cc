// The mesh metrics under the frame positions' Umeyama alignment (the
// extension *_positions_aligned; the contract's before its view Sim(3)) and
// under the attitude-anchored one (the extension, trajectory_metrics.h), on a
// straight transect like the `flat` preset's: 201 frames over 20 m along x
// (north), their true positions scattered by only kTrackScatter across the
// track, looking down at a flat seabed 2 m below.
//
// Umeyama fixes the roll about the track from the cross-track scatter alone:
// with N frames, a true scatter sigma_t and estimated positions off by
// sigma_e across the track, its roll is off by about sigma_e / (sigma_t
// sqrt(N)) (here 2 mm / (5 mm sqrt(201)) = 0.028 rad = 1.6 degrees), which
// tilts the whole mapped mesh. The frames' orientations fix that rotation
// directly, so the attitude-anchored alignment does not tilt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "core/geometry/sim3.h"
#include "pipelines/evaluate/evaluation_metrics.h"
#include "pipelines/evaluate/mesh_metrics.h"
#include "pipelines/evaluate/trajectory_metrics.h"
#include "tests/pipelines/evaluate/evaluation_fixture.h"

namespace hsmap {
namespace {

using testing::flatSeabed;

constexpr int kFrames = 201;
constexpr double kFrameSpacing = 0.1;   // m along x: a 20 m track
constexpr double kTrackScatter = 0.005;  // m, std of the true positions across the track
constexpr double kSeabedDown = 2.0;      // the cameras fly at down ~ 0
constexpr double kSwathHalfWidth = 1.5;  // the produced mesh covers east [-1.5, 1.5] m
// The cameras look ~2 m down at the seabed (h of the view Sim(3), not used here).
const MetricValue kViewDistance = MetricValue::of(kSeabedDown);

double value(const MetricValue& metric) {
  EXPECT_TRUE(metric.value.has_value()) << metric.reason;
  return metric.value.value_or(NAN);
}

// The true frames: along x, scattered across it (y, z) by kTrackScatter,
// looking down (camera z = W's down) with a degree or so of random attitude.
std::vector<TimedPose> straightTrack(std::mt19937& rng) {
  std::normal_distribution<double> scatter(0.0, kTrackScatter);
  std::normal_distribution<double> attitude(0.0, 0.02);  // rad
  std::vector<TimedPose> frames;
  for (int i = 0; i < kFrames; ++i) {
    const Eigen::Vector3d p_W_C(kFrameSpacing * i, scatter(rng), scatter(rng));
    const Eigen::Vector3d rotation_vector(attitude(rng), attitude(rng), attitude(rng));
    const Eigen::Quaterniond q_W_C(
        Eigen::AngleAxisd(rotation_vector.norm(), rotation_vector.normalized()));
    frames.push_back({36000.0 + 0.1 * i, SE3d(q_W_C, p_W_C)});
  }
  return frames;
}

// The true surface (wider than the produced mesh, so that no mapped vertex
// falls beyond its edge) and the produced mesh, both in the truth's W.
PlyMesh trueScene() { return flatSeabed(-2.0, 22.0, -2.5, 2.5, 0.25, kSeabedDown); }
PlyMesh producedMeshInTrueW() {
  return flatSeabed(-1.0, 21.0, -kSwathHalfWidth, kSwathHalfWidth, 0.25, kSeabedDown);
}

// The true-surface samples: the footprint north [0, 20] x east [-1, 1] every 5 cm.
std::vector<Eigen::Vector3d> footprintSamples() {
  std::vector<Eigen::Vector3d> samples;
  for (int i = 0; i <= 400; ++i) {
    for (int j = 0; j <= 40; ++j) samples.emplace_back(0.05 * i, -1.0 + 0.05 * j, kSeabedDown);
  }
  return samples;
}

struct BothAlignments {
  TrajectoryMetrics trajectory;
  MeshMetrics positions;
  MeshMetrics attitude;
};

BothAlignments measure(const std::vector<TimedPose>& frames_est,
                       const std::vector<TimedPose>& frames_true, const PlyMesh& mesh_est) {
  BothAlignments out;
  out.trajectory = computeTrajectoryMetrics(frames_est, frames_true, {}, {}, kViewDistance);
  EXPECT_TRUE(out.trajectory.S_true_est.has_value()) << out.trajectory.why_no_alignment;
  EXPECT_TRUE(out.trajectory.S_true_est_attitude.has_value())
      << out.trajectory.why_no_attitude_alignment;
  if (!out.trajectory.S_true_est || !out.trajectory.S_true_est_attitude) return out;
  const std::vector<MeshMetrics> mesh = computeMeshMetrics(
      mesh_est, {*out.trajectory.S_true_est, *out.trajectory.S_true_est_attitude}, trueScene(),
      footprintSamples(), 0.02);
  out.positions = mesh.at(0);
  out.attitude = mesh.at(1);
  return out;
}

// The rotation angle (rad) of a similarity about the track axis x.
double rollAboutTrack(const Sim3& S) {
  const Eigen::Matrix3d R = S.rotation().toRotationMatrix();
  return std::atan2(R(2, 1), R(1, 1));
}

TEST(AttitudeAlignedMesh, TheCrossTrackSpreadIsTheTracksScatter) {
  std::mt19937 rng(7);
  const std::vector<TimedPose> frames = straightTrack(rng);
  const TrajectoryMetrics trajectory = computeTrajectoryMetrics(frames, frames, {}, {}, kViewDistance);
  // The larger of the two sample stds across the track (201 samples each:
  // ~5 % about kTrackScatter), not the 5.8 m along it.
  EXPECT_GT(value(trajectory.alignment_cross_track_spread_m), 0.9 * kTrackScatter);
  EXPECT_LT(value(trajectory.alignment_cross_track_spread_m), 1.25 * kTrackScatter);
  // Below the table's 5 cm: it will say the roll is weakly determined.
  EXPECT_LT(value(trajectory.alignment_cross_track_spread_m), kWeakRollCrossTrackSpreadM);
}

TEST(AttitudeAlignedMesh, ASimilarityOfTheWholeEstimateCostsNothingUnderEitherAlignment) {
  std::mt19937 rng(11);
  const std::vector<TimedPose> frames_true = straightTrack(rng);
  // The run's W is the truth's rolled 2 degrees about the track (about a
  // point beside it), 2 % larger and moved: map and cameras alike.
  const Eigen::Quaterniond roll(Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()));
  const Sim3 S_est_true(1.02, roll, Eigen::Vector3d(0.3, -0.2, 0.1));
  std::vector<TimedPose> frames_est = frames_true;
  for (TimedPose& frame : frames_est) frame.T = S_est_true.transformPose(frame.T);
  PlyMesh mesh_est = producedMeshInTrueW();
  for (Eigen::Vector3d& v : mesh_est.vertices) v = S_est_true.apply(v);

  const BothAlignments result = measure(frames_est, frames_true, mesh_est);
  // Exact data: both alignments recover S_est_true^-1 (to rounding, amplified
  // by the ~1e6 condition of Umeyama's 5 mm scatter against a 20 m track).
  EXPECT_NEAR(value(result.positions.mesh_accuracy_m), 0.0, 1e-6);
  EXPECT_NEAR(value(result.attitude.mesh_accuracy_m), 0.0, 1e-6);
  EXPECT_EQ(value(result.positions.mesh_completeness), 1.0);
  EXPECT_EQ(value(result.attitude.mesh_completeness), 1.0);
}

TEST(AttitudeAlignedMesh, MillimetresOfCameraNoiseAcrossTheTrackTiltOnlyThePositionsAlignment) {
  std::mt19937 rng(13);
  const std::vector<TimedPose> frames_true = straightTrack(rng);
  // The map is exact; the cameras' positions are off by 2 mm (std) across
  // the track, their orientations exact.
  constexpr double kCameraNoise = 0.002;
  std::normal_distribution<double> noise(0.0, kCameraNoise);
  std::vector<TimedPose> frames_est = frames_true;
  for (TimedPose& frame : frames_est) frame.T.t += Eigen::Vector3d(0.0, noise(rng), noise(rng));
  const PlyMesh mesh_est = producedMeshInTrueW();

  const BothAlignments result = measure(frames_est, frames_true, mesh_est);
  const double positions = value(result.positions.mesh_accuracy_m);
  const double attitude = value(result.attitude.mesh_accuracy_m);
  std::cout << "positions-aligned mesh_accuracy_m " << positions << ", attitude-aligned " << attitude
            << "; completeness " << value(result.positions.mesh_completeness)
            << ", attitude-aligned " << value(result.attitude.mesh_completeness) << "; positions roll "
            << rollAboutTrack(*result.trajectory.S_true_est) * 180.0 / M_PI << " deg\n";

  // Attitude-anchored: R is the identity exactly (exact orientations); the
  // scale and translation absorb only the mean of the noise, ~2 mm /
  // sqrt(201) = 0.14 mm (std), so the mesh stays on the truth.
  EXPECT_LT(attitude, 5e-4);
  EXPECT_EQ(value(result.attitude.mesh_completeness), 1.0);

  // Positions: its roll about the track is off by ~sigma_e / (sigma_t
  // sqrt(N)) ~ 1.6 degrees (header comment); here well beyond a tenth of one.
  const double roll = rollAboutTrack(*result.trajectory.S_true_est);
  EXPECT_GT(std::abs(roll), 0.1 * M_PI / 180.0);
  // That tilt alone explains the error: a vertex at east y moves vertically
  // by ~roll y, and the median of |y| over the mesh's columns (east -1.5 to
  // 1.5 m every 0.25 m) is 0.75 m; the rest (the noise's mean, as above) is
  // below a millimetre.
  EXPECT_NEAR(positions, std::abs(roll) * 0.75, 0.1 * std::abs(roll) * 0.75 + 1e-3);
  // So the positions-aligned metric measures the alignment, not the mesh: clearly worse.
  EXPECT_GT(positions, 5.0 * attitude);
  EXPECT_GT(positions, 2e-3);
  // Samples more than 2 cm / |roll| off the track are no longer covered.
  EXPECT_LT(value(result.positions.mesh_completeness),
            std::min(1.0, 0.02 / std::abs(roll)) + 0.05);
}

TEST(AttitudeAlignedMesh, WithoutOrientationsThatAgreeThereIsNoAttitudeAlignment) {
  // Two frames turned by 180 degrees against each other: their R_true R_est^T
  // cancel out in the chordal mean.
  const Eigen::Quaterniond identity = Eigen::Quaterniond::Identity();
  const std::vector<TimedPose> frames_true = {{0.0, SE3d(identity, Eigen::Vector3d(0, 0, 0))},
                                              {0.1, SE3d(identity, Eigen::Vector3d(1, 0, 0))}};
  std::vector<TimedPose> frames_est = frames_true;
  frames_est[1].T.q = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
  frames_est[0].T.q = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
  const TrajectoryMetrics trajectory = computeTrajectoryMetrics(frames_est, frames_true, {}, {}, kViewDistance);
  EXPECT_FALSE(trajectory.S_true_est_attitude.has_value());
  EXPECT_NE(trajectory.why_no_attitude_alignment.find("no attitude-anchored alignment"),
            std::string::npos)
      << trajectory.why_no_attitude_alignment;
}

}  // namespace
}  // namespace hsmap
