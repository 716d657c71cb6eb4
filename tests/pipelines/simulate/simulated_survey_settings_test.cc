// The settings that change what a simulated survey records, each checked on
// a small survey against the `tiny` preset it starts from:
//   rgb.blackouts    the frames in a dropout are black, no other byte changes;
//   ins.attitude     false writes a position-only ins.csv that loads and
//                    summarises like a real one, with the same positions;
//   motion.heading_deg  the track heads that way and every frame and scan
//                    line still sees the seabed (the scene turns with it);
//   scene.slope_deg  the seabed deepens by tan(slope) per metre and the
//                    vehicle, keeping its altitude, goes down with it.
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/io/ply_io.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/survey.h"
#include "core/util/input_error.h"
#include "core/survey/survey_summary.h"
#include "core/survey/survey_truth.h"
#include "pipelines/simulate/simulate_survey.h"
#include "pipelines/simulate/simulation_config_yaml.h"
#include "tests/pipelines/simulate/tiny_survey.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

std::string fileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

SE3d toSe3(const RigidTransformConfig& transform) {
  return SE3d(transform.rotation, transform.translation_m);
}

TEST(SimulatedSurveySettings, BlackoutFramesAreBlackAndNothingElseChanges) {
  const auto& tiny = testing::tinySurvey();
  SimulationConfig config = tiny.config;
  // Times from the trajectory's start; recording starts 0.515 s after it.
  config.rgb.blackouts = {{1.0, 0.32}, {2.5, 0.1}};
  testing::TempFolder temp("blackouts");
  std::ostringstream log;
  const SimulationSummary summary = simulateSurvey(config, temp / "survey", log);
  ASSERT_EQ(summary.rgb_frames, tiny.summary.rgb_frames);

  const Survey survey = loadSurvey(temp / "survey");
  const SurveyTruth truth = loadSurveyTruth(temp / "survey");
  ASSERT_EQ(truth.rgb_poses.size(), std::size_t(survey.rgb.frameCount()));
  int black = 0;
  for (int k = 0; k < survey.rgb.frameCount(); ++k) {
    const double tau = survey.rgb.time(k) - config.start_time_s;
    const bool in_blackout = (tau >= 1.0 && tau < 1.32) || (tau >= 2.5 && tau < 2.6);
    const cv::Mat frame = survey.rgb.frame(k);
    if (in_blackout) {
      EXPECT_EQ(cv::countNonZero(frame.reshape(1)), 0) << "frame " << k << " at " << tau << " s";
      ++black;
    } else {
      // Lit seabed: no frame outside a dropout is anywhere near black.
      EXPECT_GT(cv::mean(frame)[1], 10.0) << "frame " << k << " at " << tau << " s";
      const std::string name = survey.rgb.framePath(k).filename().string();
      EXPECT_TRUE(fileBytes(survey.rgb.framePath(k)) == fileBytes(tiny.folder / "rgb" / name))
          << "frame " << k << " differs from tiny's";
    }
  }
  // 0.32 s and 0.1 s at 25 Hz: 8 and 2 or 3 frames, whatever the phase.
  EXPECT_GE(black, 10);
  EXPECT_LE(black, 11);
  // The other sensors and the truth are untouched.
  for (const char* file : {"uhi/cube.raw", "uhi/lines.csv", "nav/ins.csv", "rgb/frames.csv",
                           "truth/rgb_poses.csv", "truth/uhi_poses.csv", "survey.yaml"}) {
    EXPECT_TRUE(fileBytes(temp / "survey" / file) == fileBytes(tiny.folder / file)) << file;
  }
}

TEST(SimulatedSurveySettings, InsWithoutAttitudeLoadsAndKeepsThePositions) {
  const auto& tiny = testing::tinySurvey();
  SimulationConfig config = tiny.config;
  config.ins.attitude = false;
  testing::TempFolder temp("no_attitude");
  std::ostringstream log;
  simulateSurvey(config, temp / "survey", log);

  std::ifstream csv(temp / "survey" / "nav" / "ins.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "t,lat,lon,depth");

  const Survey survey = loadSurvey(temp / "survey");
  const Survey with_attitude = loadSurvey(tiny.folder);
  EXPECT_FALSE(survey.ins.has_attitude);
  ASSERT_TRUE(with_attitude.ins.has_attitude);
  ASSERT_EQ(survey.ins.fixes.size(), with_attitude.ins.fixes.size());
  ASSERT_GT(survey.ins.fixes.size(), 10u);
  for (std::size_t i = 0; i < survey.ins.fixes.size(); ++i) {
    const InsFix& fix = survey.ins.fixes[i];
    const InsFix& reference = with_attitude.ins.fixes[i];
    EXPECT_EQ(fix.t, reference.t);
    EXPECT_EQ(fix.lat_deg, reference.lat_deg);
    EXPECT_EQ(fix.lon_deg, reference.lon_deg);
    EXPECT_EQ(fix.depth_m, reference.depth_m);
    EXPECT_EQ(fix.roll_deg, 0.0);
    EXPECT_EQ(fix.pitch_deg, 0.0);
    EXPECT_EQ(fix.heading_deg, 0.0);
  }
  // What `hsmap inspect` prints.
  std::ostringstream printed;
  printSurveySummary(printed, summarizeSurvey(survey));
  EXPECT_NE(printed.str().find("position only (no attitude)"), std::string::npos)
      << printed.str();
}

// The UHI intrinsics' guess (issue 44): survey.yaml's uhi.camera is the
// truth moved by the stated errors, with the stated sigmas; the truth and
// the rendered cube keep the true camera. Read from a configuration file as
// users write it.
TEST(SimulatedSurveySettings, UhiIntrinsicsGuessIsTheTruthMovedByTheStatedErrors) {
  const auto& tiny = testing::tinySurvey();
  testing::TempFolder temp("uhi_intrinsics");
  testing::writeText(temp / "config.yaml",
                     "format: hsmap-simulation/1\n"
                     "preset: tiny\n"
                     "calibration:\n"
                     "  error_uhi_focal_rel: 0.01\n"
                     "  error_uhi_cx_px: 3\n"
                     "  error_uhi_distortion: [0.02, 0]\n"
                     "  uhi_camera_sigma: {f: 15, cx: 3, distortion: [0.02, 0.01]}\n");
  const SimulationConfig config = readSimulationConfig(temp / "config.yaml");
  std::ostringstream log;
  simulateSurvey(config, temp / "survey", log);
  const Survey survey = loadSurvey(temp / "survey");
  const PushbroomParameters& truth = tiny.config.uhi.camera;
  const PushbroomParameters& guess = survey.config.uhi.camera;
  EXPECT_DOUBLE_EQ(guess.f, truth.f * 1.01);
  EXPECT_DOUBLE_EQ(guess.cx, truth.cx + 3.0);
  EXPECT_DOUBLE_EQ(guess.distortion[0], truth.distortion[0] + 0.02);
  EXPECT_DOUBLE_EQ(guess.distortion[1], truth.distortion[1]);
  ASSERT_TRUE(survey.config.uhi.camera_sigma.has_value());
  EXPECT_EQ(survey.config.uhi.camera_sigma->f, 15.0);
  EXPECT_EQ(survey.config.uhi.camera_sigma->distortion[1], 0.01);
  const SurveyTruth survey_truth = loadSurveyTruth(temp / "survey");
  EXPECT_EQ(survey_truth.calibration.uhi_camera.f, truth.f);
  EXPECT_EQ(survey_truth.calibration.uhi_camera.cx, truth.cx);
  // The cube is rendered through the true camera: the same bytes as tiny's.
  EXPECT_EQ(testing::readText(temp / "survey" / "uhi" / "cube.raw"), testing::readText(tiny.folder / "uhi" / "cube.raw"));
}

// The RGB intrinsics' guess (issue 44), as the UHI's: survey.yaml's
// rgb.camera is the truth moved by the stated errors, with the stated
// sigmas; the truth and the rendered frames keep the true camera.
TEST(SimulatedSurveySettings, RgbIntrinsicsGuessIsTheTruthMovedByTheStatedErrors) {
  const auto& tiny = testing::tinySurvey();
  testing::TempFolder temp("rgb_intrinsics");
  testing::writeText(temp / "config.yaml",
                     "format: hsmap-simulation/1\n"
                     "preset: tiny\n"
                     "calibration:\n"
                     "  error_rgb_focal_rel: 0.01\n"
                     "  error_rgb_cx_px: 3\n"
                     "  error_rgb_cy_px: -2\n"
                     "  error_rgb_distortion: [0.01, 0, 0, 0, 0]\n"
                     "  rgb_camera_sigma: {fx: 8, fy: 8, cx: 4, cy: 4, distortion: [0.02, 0.02, 0, 0, 0]}\n");
  const SimulationConfig config = readSimulationConfig(temp / "config.yaml");
  std::ostringstream log;
  simulateSurvey(config, temp / "survey", log);
  const Survey survey = loadSurvey(temp / "survey");
  const PinholeRadtanParameters& truth = tiny.config.rgb.camera;
  const PinholeRadtanParameters& guess = survey.config.rgb.camera;
  EXPECT_DOUBLE_EQ(guess.fx, truth.fx * 1.01);
  EXPECT_DOUBLE_EQ(guess.fy, truth.fy * 1.01);
  EXPECT_DOUBLE_EQ(guess.cx, truth.cx + 3.0);
  EXPECT_DOUBLE_EQ(guess.cy, truth.cy - 2.0);
  EXPECT_DOUBLE_EQ(guess.distortion[0], truth.distortion[0] + 0.01);
  for (std::size_t i = 1; i < 5; ++i) EXPECT_EQ(guess.distortion[i], truth.distortion[i]) << i;
  ASSERT_TRUE(survey.config.rgb.camera_sigma.has_value());
  EXPECT_EQ(survey.config.rgb.camera_sigma->fx, 8.0);
  EXPECT_EQ(survey.config.rgb.camera_sigma->cy, 4.0);
  EXPECT_EQ(survey.config.rgb.camera_sigma->distortion[1], 0.02);
  EXPECT_EQ(survey.config.rgb.camera_sigma->distortion[4], 0.0);
  const SurveyTruth survey_truth = loadSurveyTruth(temp / "survey");
  EXPECT_EQ(survey_truth.calibration.rgb_camera.fx, truth.fx);
  EXPECT_EQ(survey_truth.calibration.rgb_camera.cx, truth.cx);
  EXPECT_EQ(survey_truth.calibration.rgb_camera.distortion, truth.distortion);
  // The frames are rendered through the true camera: the same bytes as tiny's.
  EXPECT_EQ(testing::readText(temp / "survey" / "rgb" / "frame_000010.png"), testing::readText(tiny.folder / "rgb" / "frame_000010.png"));
  // A bad setting is named by its key.
  testing::writeText(temp / "bad.yaml",
                     "format: hsmap-simulation/1\n"
                     "preset: tiny\n"
                     "calibration:\n"
                     "  error_rgb_distortion: [0.01, 0]\n");
  try {
    readSimulationConfig(temp / "bad.yaml");
    ADD_FAILURE() << "a 2-entry error_rgb_distortion was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("key calibration.error_rgb_distortion: expected a list of 5 numbers, got a list of 2"),
              std::string::npos)
        << error.what();
  }
}

TEST(SimulatedSurveySettings, TurnedTrackHeadsThatWayAndAlwaysSeesTheSeabed) {
  SimulationConfig config = *simulationPreset("tiny");
  config.motion.heading_deg = 120.0;  // south-east: off the unturned scene entirely
  testing::TempFolder temp("heading");
  std::ostringstream log;
  const SimulationSummary summary = simulateSurvey(config, temp / "survey", log);
  const SurveyTruth truth = loadSurveyTruth(temp / "survey");
  const Survey survey = loadSurvey(temp / "survey");
  const PlyMesh scene = readPly(truth.scene_path);
  const MeshRayCaster caster(scene.vertices, scene.triangles);

  // The body follows the path exactly (the wander yaws it, not its track):
  // its displacement points along the heading.
  const SE3d T_C_B = toSe3(truth.calibration.T_B_C).inverse();
  const Eigen::Vector3d first_B = (truth.rgb_poses.front().T_W_X * T_C_B).t;
  const Eigen::Vector3d last_B = (truth.rgb_poses.back().T_W_X * T_C_B).t;
  const Eigen::Vector2d travel = (last_B - first_B).head<2>();
  ASSERT_GT(travel.norm(), 0.5);
  EXPECT_NEAR(std::atan2(travel.y(), travel.x()) / kDegToRad, 120.0, 1e-6);

  // Every frame's corners and centre, and both ends of every scan line, hit
  // the scene: the seabed was turned with the track.
  const PinholeRadtanCamera rgb_camera(truth.calibration.rgb_camera);
  const double w = rgb_camera.width() - 1.0, h = rgb_camera.height() - 1.0;
  for (std::size_t k = 0; k < truth.rgb_poses.size(); ++k) {
    const SE3d& T_W_C = truth.rgb_poses[k].T_W_X;
    for (const Eigen::Vector2d pixel : {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0),
                                        Eigen::Vector2d(0, h), Eigen::Vector2d(w, h),
                                        Eigen::Vector2d(w / 2, h / 2)}) {
      const auto ray_C = rgb_camera.unproject(pixel);
      ASSERT_TRUE(ray_C.has_value());
      EXPECT_TRUE(caster.intersect(Ray{T_W_C.t, (T_W_C.q * *ray_C).normalized()}).hit())
          << "frame " << k << " pixel " << pixel.transpose();
    }
  }
  for (int k = 0; k < survey.rgb.frameCount(); k += 10) {
    EXPECT_GT(cv::mean(survey.rgb.frame(k))[1], 10.0) << "frame " << k;
  }
  const PushbroomCamera uhi_camera(truth.calibration.uhi_camera);
  for (std::size_t j = 0; j < truth.uhi_poses.size(); ++j) {
    const SE3d& T_W_U = truth.uhi_poses[j].T_W_U;
    for (const double u : {0.0, uhi_camera.samples() - 1.0}) {
      const auto ray_U = uhi_camera.unproject(u);
      ASSERT_TRUE(ray_U.has_value());
      EXPECT_TRUE(caster.intersect(Ray{T_W_U.t, (T_W_U.q * *ray_U).normalized()}).hit())
          << "line " << j << " sample " << u;
    }
  }
  EXPECT_GT(summary.reflectance_valid_pixels, 10000);
}

// Slope along the track (downhill north, the way the vehicle flies): the
// same survey with and without it.
TEST(SimulatedSurveySettings, SlopedSeabedDeepensAlongItsDirectionAndTheVehicleFollows) {
  SimulationConfig flat = *simulationPreset("tiny");
  flat.motion.length_m = 6.0;
  flat.rgb.camera = scaledRgbCamera(96, 54);
  flat.uhi.camera = scaledUhiCamera(64);
  flat.uhi.bands = 4;
  SimulationConfig sloped = flat;
  sloped.scene.slope_deg = 15.0;
  sloped.scene.slope_direction_deg = 0.0;
  const double gradient = std::tan(15.0 * kDegToRad);
  testing::TempFolder temp("slope");
  std::ostringstream log;
  simulateSurvey(flat, temp / "flat", log);
  simulateSurvey(sloped, temp / "sloped", log);
  const SurveyTruth flat_truth = loadSurveyTruth(temp / "flat");
  const SurveyTruth sloped_truth = loadSurveyTruth(temp / "sloped");

  // The meshes differ by the plane exactly (same grid, same relief).
  const PlyMesh flat_mesh = readPly(flat_truth.scene_path);
  const PlyMesh sloped_mesh = readPly(sloped_truth.scene_path);
  ASSERT_EQ(flat_mesh.vertices.size(), sloped_mesh.vertices.size());
  for (std::size_t i = 0; i < flat_mesh.vertices.size(); i += 97) {
    const Eigen::Vector3d& p = flat_mesh.vertices[i];
    EXPECT_NEAR(sloped_mesh.vertices[i].z() - p.z(), gradient * p.x(), 1e-9) << "vertex " << i;
  }

  // Two points 4 m apart along the slope: the depth grows by tan(slope) x 4 m
  // up to the low-relief undulation (< 0.4 m peak to peak).
  const MeshRayCaster caster(sloped_mesh.vertices, sloped_mesh.triangles);
  auto depthAt = [&](double north, double east) {
    const RayHit hit = caster.intersect(Ray{Eigen::Vector3d(north, east, 0.0), Eigen::Vector3d::UnitZ()});
    EXPECT_TRUE(hit.hit());
    return hit.distance;
  };
  EXPECT_NEAR(depthAt(4.5, 0.0) - depthAt(0.5, 0.0), gradient * 4.0, 0.4);

  // The vehicle keeps its altitude: its depth grows by tan(slope) x the
  // distance flown, beyond what the relief alone does. Between frames away
  // from the track's ends only: the terrain envelope (terrain_envelope.h)
  // takes the uphill minimum over 1 m and smooths it over 1 m more, which
  // shifts a plane by a constant except where those windows are clamped.
  const SE3d T_C_B = toSe3(sloped_truth.calibration.T_B_C).inverse();
  ASSERT_EQ(flat_truth.rgb_poses.size(), sloped_truth.rgb_poses.size());
  auto body = [&](const SurveyTruth& truth, std::size_t k) { return (truth.rgb_poses[k].T_W_X * T_C_B).t; };
  std::size_t first = 0, last = 0;
  for (std::size_t k = 0; k < sloped_truth.rgb_poses.size(); ++k) {
    const double north = body(sloped_truth, k).x();
    if (north < 2.1) first = k;
    if (north < flat.motion.length_m - 1.1) last = k;
  }
  ASSERT_GT(last, first + 50);
  const double distance = body(sloped_truth, last).x() - body(sloped_truth, first).x();
  const double sloped_descent = body(sloped_truth, last).z() - body(sloped_truth, first).z();
  const double flat_descent = body(flat_truth, last).z() - body(flat_truth, first).z();
  EXPECT_NEAR(sloped_descent - flat_descent, gradient * distance, 0.05)
      << "flew " << distance << " m";
  EXPECT_NEAR(sloped_descent, gradient * distance, 0.4);
}

}  // namespace
}  // namespace hsmap
