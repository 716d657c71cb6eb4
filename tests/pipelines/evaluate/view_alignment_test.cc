// The frames' view Sim(3) (view_alignment.h, view_distance.h) and the uhi
// and mesh metrics through it (trajectory_metrics.h), on a straight transect
// like the `flat` preset's: 201 frames over 20 m along x (north), looking
// down at a flat seabed kSeabedDown below with a degree or so of random
// attitude, every scan line posed 0.1 m beside its frame's camera.
//
// Along a straight track the camera positions alone fix the roll about the
// track only through their sideways scatter (none at all when the track is
// exactly straight); the view points, h below the cameras, fix it through
// the cameras' orientations.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "core/geometry/sim3.h"
#include "core/raycast/mesh_ray_caster.h"
#include "pipelines/evaluate/mesh_metrics.h"
#include "pipelines/evaluate/trajectory_metrics.h"
#include "pipelines/evaluate/view_alignment.h"
#include "pipelines/evaluate/view_distance.h"
#include "tests/pipelines/evaluate/evaluation_fixture.h"

namespace hsmap {
namespace {

using testing::flatSeabed;

constexpr int kFrames = 201;
constexpr double kFrameSpacing = 0.1;  // m along x: a 20 m track
constexpr double kSeabedDown = 2.0;    // the cameras fly at down ~ 0
constexpr double kDegToRad = M_PI / 180.0;

double value(const MetricValue& metric) {
  EXPECT_TRUE(metric.value.has_value()) << metric.reason;
  return metric.value.value_or(NAN);
}

// The true frames along x, scattered across it by `scatter` (0: exactly
// straight), camera z down with ~1 degree of random attitude.
std::vector<TimedPose> straightTrack(std::mt19937& rng, double scatter) {
  std::normal_distribution<double> sideways(0.0, 1.0);
  std::normal_distribution<double> attitude(0.0, 0.02);  // rad
  std::vector<TimedPose> frames;
  for (int i = 0; i < kFrames; ++i) {
    const Eigen::Vector3d p_W_C(kFrameSpacing * i, scatter * sideways(rng), scatter * sideways(rng));
    const Eigen::Vector3d rotation_vector(attitude(rng), attitude(rng), attitude(rng));
    const Eigen::Quaterniond q_W_C(Eigen::AngleAxisd(rotation_vector.norm(), rotation_vector.normalized()));
    frames.push_back({36000.0 + 0.1 * i, SE3d(q_W_C, p_W_C)});
  }
  return frames;
}

// One scan line per frame, the UHI 0.1 m to the camera's right, turned 3
// degrees about its x axis.
std::vector<LinePose> linesOf(const std::vector<TimedPose>& frames) {
  const SE3d T_C_U(Eigen::Quaterniond(Eigen::AngleAxisd(3.0 * kDegToRad, Eigen::Vector3d::UnitX())),
                   Eigen::Vector3d(0.1, 0.0, 0.0));
  std::vector<LinePose> lines;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    lines.push_back({static_cast<long long>(k), frames[k].t + 0.01, frames[k].T * T_C_U});
  }
  return lines;
}

// The true surface and the produced mesh (in the truth's W): the seabed,
// the mesh over east [-1.5, 1.5] m, and true-surface samples every 5 cm
// over north [0, 20] x east [-1, 1].
PlyMesh trueScene() { return flatSeabed(-2.0, 22.0, -2.5, 2.5, 0.25, kSeabedDown); }
PlyMesh producedMeshInTrueW() { return flatSeabed(-1.0, 21.0, -1.5, 1.5, 0.25, kSeabedDown); }
std::vector<Eigen::Vector3d> footprintSamples() {
  std::vector<Eigen::Vector3d> samples;
  for (int i = 0; i <= 400; ++i) {
    for (int j = 0; j <= 40; ++j) samples.emplace_back(0.05 * i, -1.0 + 0.05 * j, kSeabedDown);
  }
  return samples;
}

// The view distance of these frames over trueScene().
MetricValue viewDistance(const std::vector<TimedPose>& frames_true) {
  const PlyMesh scene = trueScene();
  const MeshRayCaster caster(scene.vertices, scene.triangles);
  return medianViewDistance(frames_true, caster).h_m;
}

// The rotation angle (rad) of a similarity about the track axis x.
double rollAboutTrack(const Sim3& S) {
  const Eigen::Matrix3d R = S.rotation().toRotationMatrix();
  return std::atan2(R(2, 1), R(1, 1));
}

TEST(ViewDistance, IsTheMedianDistanceAlongTheTrueOpticalAxesToTheTrueSurface) {
  std::mt19937 rng(3);
  std::vector<TimedPose> frames = straightTrack(rng, 0.01);
  // Along the axis a: the seabed's down minus the camera's, over a's down component.
  std::vector<double> expected;
  for (const TimedPose& frame : frames) {
    const Eigen::Vector3d axis = frame.T.q * Eigen::Vector3d::UnitZ();
    expected.push_back((kSeabedDown - frame.T.t.z()) / axis.z());
  }
  std::nth_element(expected.begin(), expected.begin() + kFrames / 2, expected.end());
  const PlyMesh scene = trueScene();
  const MeshRayCaster caster(scene.vertices, scene.triangles);
  const ViewDistance all = medianViewDistance(frames, caster);
  EXPECT_NEAR(value(all.h_m), expected[kFrames / 2], 1e-12);
  EXPECT_EQ(all.frames_hit, kFrames);
  EXPECT_EQ(all.frames_missed, 0);

  // Cameras looking up see nothing of the seabed.
  for (TimedPose& frame : frames) {
    frame.T.q = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX())) * frame.T.q;
  }
  const ViewDistance none = medianViewDistance(frames, caster);
  EXPECT_FALSE(none.h_m.value.has_value());
  EXPECT_NE(none.h_m.reason.find("no true frame's optical axis meets truth/scene.ply"), std::string::npos)
      << none.h_m.reason;
  EXPECT_EQ(none.frames_missed, kFrames);
}

TEST(ViewAlignment, ARunThatIsTheTruthUnderASimilarityIsRecoveredInOneFit) {
  std::mt19937 rng(5);
  const std::vector<TimedPose> frames_true = straightTrack(rng, 0.005);
  // The run's W: 30 % larger, turned 25 degrees about an oblique axis, moved.
  const Sim3 S_est_true(1.3, Eigen::Quaterniond(Eigen::AngleAxisd(25.0 * kDegToRad, Eigen::Vector3d(1, -2, 0.5).normalized())),
                        Eigen::Vector3d(4.0, -2.0, 1.0));
  std::vector<TimedPose> frames_est = frames_true;
  for (TimedPose& frame : frames_est) frame.T = S_est_true.transformPose(frame.T);

  const ViewAlignment view = alignFramesByView(frames_est, frames_true, 2.0);
  // The start (ratio of the centres' spreads) is already the scale, so the
  // first Umeyama fit is exact and the iteration stops.
  EXPECT_EQ(view.iterations, 1);
  const Sim3 S_true_est = S_est_true.inverse();
  EXPECT_NEAR(view.S_true_est.scale(), S_true_est.scale(), 1e-12);
  EXPECT_NEAR(view.S_true_est.rotation().angularDistance(S_true_est.rotation()), 0.0, 1e-10);
  for (const TimedPose& frame : frames_true) {
    EXPECT_NEAR((view.S_true_est.apply(S_est_true.apply(frame.T.t)) - frame.T.t).norm(), 0.0, 1e-9);
  }
}

TEST(ViewAlignment, OnAnExactlyStraightTrackOnlyTheViewAlignmentRecoversTheRun) {
  std::mt19937 rng(7);
  // No scatter: the camera centres lie on one line, so their own Umeyama
  // cannot say how the run is rolled about it.
  const std::vector<TimedPose> frames_true = straightTrack(rng, 0.0);
  const std::vector<LinePose> lines_true = linesOf(frames_true);
  // The run: the truth rolled 10 degrees about the track, 5 % smaller, moved.
  const Sim3 S_est_true(0.95, Eigen::Quaterniond(Eigen::AngleAxisd(10.0 * kDegToRad, Eigen::Vector3d::UnitX())),
                        Eigen::Vector3d(0.3, -0.2, 0.1));
  std::vector<TimedPose> frames_est = frames_true;
  for (TimedPose& frame : frames_est) frame.T = S_est_true.transformPose(frame.T);
  std::vector<LinePose> lines_est = lines_true;
  for (LinePose& line : lines_est) line.T = S_est_true.transformPose(line.T);
  PlyMesh mesh_est = producedMeshInTrueW();
  for (Eigen::Vector3d& v : mesh_est.vertices) v = S_est_true.apply(v);

  const TrajectoryMetrics metrics =
      computeTrajectoryMetrics(frames_est, frames_true, lines_est, lines_true, viewDistance(frames_true));
  // Positions alone: undetermined, and saying so.
  EXPECT_FALSE(metrics.S_true_est.has_value());
  EXPECT_FALSE(metrics.uhi_position_rmse_positions_aligned_m.value.has_value());
  EXPECT_NE(metrics.uhi_rotation_rmse_positions_aligned_deg.reason.find("collinear"), std::string::npos)
      << metrics.uhi_rotation_rmse_positions_aligned_deg.reason;
  // The view Sim(3): the run is the truth, and scores 0.
  ASSERT_TRUE(metrics.S_true_est_view.has_value()) << metrics.why_no_view_alignment;
  EXPECT_NEAR(rollAboutTrack(*metrics.S_true_est_view), -10.0 * kDegToRad, 1e-10);
  EXPECT_NEAR(metrics.S_true_est_view->scale(), 1.0 / 0.95, 1e-12);
  EXPECT_NEAR(value(metrics.uhi_position_rmse_m), 0.0, 1e-9);
  EXPECT_NEAR(value(metrics.uhi_rotation_rmse_deg), 0.0, 1e-7);
  const std::vector<MeshMetrics> mesh = computeMeshMetrics(
      mesh_est, {*metrics.S_true_est_view}, trueScene(), footprintSamples(), 0.02);
  EXPECT_NEAR(value(mesh[0].mesh_accuracy_m), 0.0, 1e-9);
  EXPECT_EQ(value(mesh[0].mesh_completeness), 1.0);
}

TEST(ViewAlignment, CameraNoiseAcrossTheTrackTiltsThePositionsAlignmentButNotTheViewOne) {
  std::mt19937 rng(13);
  const std::vector<TimedPose> frames_true = straightTrack(rng, 0.005);
  const std::vector<LinePose> lines_true = linesOf(frames_true);
  // The scan lines and the map are exact; the cameras' positions are off by
  // 2 mm (std) across the track, their orientations exact.
  std::normal_distribution<double> noise(0.0, 0.002);
  std::vector<TimedPose> frames_est = frames_true;
  for (TimedPose& frame : frames_est) frame.T.t += Eigen::Vector3d(0.0, noise(rng), noise(rng));

  const TrajectoryMetrics metrics =
      computeTrajectoryMetrics(frames_est, frames_true, lines_true, lines_true, viewDistance(frames_true));
  ASSERT_TRUE(metrics.S_true_est.has_value()) << metrics.why_no_alignment;
  ASSERT_TRUE(metrics.S_true_est_view.has_value()) << metrics.why_no_view_alignment;
  const double roll_positions = rollAboutTrack(*metrics.S_true_est);
  const double roll_view = rollAboutTrack(*metrics.S_true_est_view);
  std::cout << "roll about the track: positions " << roll_positions / kDegToRad << " deg, view "
            << roll_view / kDegToRad << " deg (" << metrics.view_alignment_iterations
            << " Umeyama fits); uhi_rotation_rmse_deg " << value(metrics.uhi_rotation_rmse_deg)
            << ", positions-aligned " << value(metrics.uhi_rotation_rmse_positions_aligned_deg) << "\n";
  // Positions: the roll is off by ~sigma_e / (sigma_t sqrt(N)) = 2 mm / (5 mm
  // sqrt(201)) ~ 1.6 degrees (attitude_aligned_mesh_test.cc), and every
  // (exact) scan line's orientation with it.
  EXPECT_GT(std::abs(roll_positions), 0.1 * kDegToRad);
  EXPECT_NEAR(value(metrics.uhi_rotation_rmse_positions_aligned_deg), std::abs(roll_positions) / kDegToRad,
              0.1 * std::abs(roll_positions) / kDegToRad);
  // View: the view points 2 m below pin the roll to ~2 mm / (2 m sqrt(2 N))
  // ~ 0.003 degrees.
  EXPECT_LT(std::abs(roll_view), 0.02 * kDegToRad);
  EXPECT_LT(value(metrics.uhi_rotation_rmse_deg), 0.02);
  EXPECT_GT(value(metrics.uhi_rotation_rmse_positions_aligned_deg), 5.0 * value(metrics.uhi_rotation_rmse_deg));
  // Noise makes the view points' scale differ from the start: it took more
  // than one fit to settle.
  EXPECT_GT(metrics.view_alignment_iterations, 1);

  // The exact mesh, mapped by either: the view Sim(3) leaves it on the
  // seabed; the positions' tilt lifts a vertex 0.75 m aside (the median
  // |east|) by ~roll 0.75 m.
  const std::vector<MeshMetrics> mesh =
      computeMeshMetrics(producedMeshInTrueW(), {*metrics.S_true_est_view, *metrics.S_true_est}, trueScene(),
                         footprintSamples(), 0.02);
  EXPECT_LT(value(mesh[0].mesh_accuracy_m), 5e-4);
  EXPECT_GT(value(mesh[1].mesh_accuracy_m), 2e-3);
  EXPECT_EQ(value(mesh[0].mesh_completeness), 1.0);
}

TEST(ViewAlignment, TheScaleIsAFixedPointOfTheViewFit) {
  std::mt19937 rng(17);
  const std::vector<TimedPose> frames_true = straightTrack(rng, 0.05);
  // A run 10 % larger with centimetres of smooth error and a degree of
  // orientation noise: the start (ratio of spreads) is not the fixed point.
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<TimedPose> frames_est = frames_true;
  for (std::size_t i = 0; i < frames_est.size(); ++i) {
    TimedPose& frame = frames_est[i];
    frame.T.t = 1.1 * frame.T.t + Eigen::Vector3d(0.0, 0.03 * std::sin(0.05 * i), 0.02 * std::cos(0.03 * i));
    const Eigen::Vector3d turn(0.01 * noise(rng), 0.01 * noise(rng), 0.01 * noise(rng));
    frame.T.q = Eigen::Quaterniond(Eigen::AngleAxisd(turn.norm(), turn.normalized())) * frame.T.q;
  }
  constexpr double h = 2.0;
  const ViewAlignment view = alignFramesByView(frames_est, frames_true, h);
  EXPECT_GT(view.iterations, 1);
  // Refitting Umeyama with the view points at h / s gives s back.
  const double s = view.S_true_est.scale();
  std::vector<Eigen::Vector3d> sources, targets;
  for (const TimedPose& frame : frames_est) sources.push_back(frame.T.t);
  for (const TimedPose& frame : frames_est) sources.push_back(frame.T.t + (h / s) * (frame.T.q * Eigen::Vector3d::UnitZ()));
  for (const TimedPose& frame : frames_true) targets.push_back(frame.T.t);
  for (const TimedPose& frame : frames_true) targets.push_back(frame.T.t + h * (frame.T.q * Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(alignUmeyama(sources, targets).scale(), s, 1e-10 * s);
  EXPECT_NEAR(s, 1.0 / 1.1, 0.01);
}

TEST(ViewAlignment, CoincidentCameraCentresLeaveTheScaleUndetermined) {
  std::mt19937 rng(19);
  std::vector<TimedPose> frames = straightTrack(rng, 0.0);
  for (TimedPose& frame : frames) frame.T.t = Eigen::Vector3d(1.0, 2.0, 0.0);
  try {
    alignFramesByView(frames, frames, 2.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("camera centres all coincide"), std::string::npos) << e.what();
  }
  const TrajectoryMetrics metrics = computeTrajectoryMetrics(frames, frames, linesOf(frames), linesOf(frames),
                                                             MetricValue::of(2.0));
  EXPECT_FALSE(metrics.uhi_position_rmse_m.value.has_value());
  EXPECT_NE(metrics.uhi_position_rmse_m.reason.find("no view alignment of the frames"), std::string::npos);
}

}  // namespace
}  // namespace hsmap
