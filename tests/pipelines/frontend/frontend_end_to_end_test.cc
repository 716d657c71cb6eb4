// The whole front-end on simulated surveys: every frame posed and the
// trajectory's shape within 0.5 % of the path length after a Sim(3)
// alignment; a run of black frames reported as one loss with its exact
// frame range, and the frames after it posed in the same frame F; every
// posed frame keeps the observations its pose rests on.
#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/survey/survey.h"
#include "core/survey/truth_files.h"
#include "pipelines/frontend/frontend_outputs.h"
#include "pipelines/frontend/frontend_runner.h"
#include "tests/pipelines/frontend/frontend_test_support.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

testing::SimulatedSurveysCleanup cleanup;

TEST(FrontendEndToEnd, TinySurveyEveryFramePosedWithinHalfAPercentOfThePath) {
  const auto folder = testing::simulatedFrontendSurvey("tiny", *simulationPreset("tiny"));
  const Survey survey = loadSurvey(folder);
  int progress_calls = 0;
  const FrontendResult result =
      runFrontend(survey, FrontendOptions{}, [&](int done, int total, double fps) {
        ++progress_calls;
        EXPECT_LE(done, total);
        EXPECT_GE(fps, 0.0);
      });
  std::cout << result.summary() << "\n";
  EXPECT_EQ(progress_calls, survey.rgb.frameCount());
  ASSERT_EQ(int(result.frames.size()), survey.rgb.frameCount());
  EXPECT_EQ(result.posedFrameCount(), survey.rgb.frameCount());
  EXPECT_TRUE(result.losses.empty());
  EXPECT_EQ(result.segments.size(), 1u);
  EXPECT_GE(result.map.keyframes().size(), 3u);
  EXPECT_GE(result.map.validLandmarkCount(), 100u);

  const auto truth = readTruthPoses(folder / "truth" / "rgb_poses.csv");
  const testing::AlignedError error = testing::alignedFrameError(result, truth);
  std::cout << "aligned rms " << error.rms_m << " m over a " << error.path_length_m << " m path ("
            << error.percentOfPath() << " %)\n";
  EXPECT_LE(error.percentOfPath(), 0.5);

  // Every landmark is seen by at least two keyframes, every observation
  // reprojects close to its pixel.
  const PinholeRadtanCamera camera(survey.config.rgb.camera);
  double worst = 0.0;
  for (const Keyframe& k : result.map.keyframes()) {
    for (const auto& o : k.observations) {
      const Landmark& l = result.map.landmark(o.landmark_id);
      ASSERT_TRUE(l.valid);
      const Eigen::Vector3d p_C = k.T_F_C.inverse() * l.p_F;
      ASSERT_GT(p_C.z(), 0.0);
      worst = std::max(worst, (camera.project(p_C) - o.pixel).norm());
    }
  }
  EXPECT_LE(worst, 3.0);
  for (const Landmark& l : result.map.landmarks()) {
    if (l.valid) EXPECT_GE(l.keyframe_ids.size(), 2u);
  }
}

// The observations every posed frame's pose rests on (for the re-posing of
// every frame after geo-referencing): sorted, none for a frame not posed, at
// least the minimum inlier count per posed frame, only landmarks of the map,
// and nearly all reprojecting through the frame's final T_F_C within the
// inlier threshold of their pixel.
void expectFrameObservationsFitTheirFrames(const FrontendResult& result, const Survey& survey,
                                           const FrontendOptions& options) {
  const PinholeRadtanCamera camera(survey.config.rgb.camera);
  const double threshold_px = options.inlier_threshold_px * options.errorScale(camera.width());
  for (std::size_t i = 1; i < result.frame_observations.size(); ++i) {
    const FrameObservation& a = result.frame_observations[i - 1];
    const FrameObservation& b = result.frame_observations[i];
    ASSERT_TRUE(a.frame < b.frame || (a.frame == b.frame && a.landmark < b.landmark)) << "row " << i;
  }
  std::size_t counted = 0, close = 0;
  int fewest = std::numeric_limits<int>::max();
  for (const FrameRecord& f : result.frames) {
    const auto observations = result.observationsOfFrame(f.index);
    if (!f.posed) {
      EXPECT_TRUE(observations.empty()) << "frame " << f.index;
      continue;
    }
    fewest = std::min(fewest, int(observations.size()));
    EXPECT_GE(int(observations.size()), options.min_pose_inliers) << "frame " << f.index;
    EXPECT_LE(int(observations.size()), f.inliers) << "frame " << f.index;
    const SE3d T_C_F = f.T_F_C.inverse();
    for (const FrameObservation& o : observations) {
      ASSERT_GE(o.landmark, 0);
      ASSERT_LT(o.landmark, int(result.map.landmarks().size()));
      const Landmark& l = result.map.landmark(o.landmark);
      ASSERT_TRUE(l.valid) << "landmark " << o.landmark;
      const Eigen::Vector3d p_C = T_C_F * l.p_F;
      ++counted;
      if (p_C.z() > 0.0 && (camera.project(p_C) - Eigen::Vector2d(o.u, o.v)).norm() <= threshold_px) ++close;
    }
  }
  EXPECT_EQ(counted, result.frame_observations.size());  // none of a frame not posed
  const double fraction = double(close) / double(std::max<std::size_t>(counted, 1));
  std::cout << result.frame_observations.size() << " frame observations, fewest per posed frame " << fewest
            << ", " << 100.0 * fraction << " % within " << threshold_px << " px\n";
  EXPECT_GE(fraction, 0.95);
}

TEST(FrontendEndToEnd, TinySurveyEveryPosedFrameKeepsTheObservationsItsPoseRestsOn) {
  const auto folder = testing::simulatedFrontendSurvey("tiny", *simulationPreset("tiny"));
  const Survey survey = loadSurvey(folder);
  // A tight BA outlier threshold, so that bundle adjustment removes landmarks
  // (~2 %) that frames were posed from: their observations must be dropped
  // and the others mapped to the ids of the final map (with the default, no
  // landmark of `tiny` is removed and the ids happen to stay the same).
  FrontendOptions options;
  options.ba_outlier_px = 0.6;
  const FrontendResult result = runFrontend(survey, options);
  expectFrameObservationsFitTheirFrames(result, survey, options);

  // The same after writing and reading RUN/frontend/.
  testing::TempFolder run;
  writeFrontendOutputs(run.path(), result);
  const FrontendResult read = readFrontendOutputs(run.path());
  ASSERT_EQ(read.frame_observations.size(), result.frame_observations.size());
  for (std::size_t i = 0; i < result.frame_observations.size(); ++i) {
    const FrameObservation& a = result.frame_observations[i];
    const FrameObservation& b = read.frame_observations[i];
    ASSERT_TRUE(a.frame == b.frame && a.landmark == b.landmark && a.u == b.u && a.v == b.v) << "row " << i;
  }
}

// A survey long enough for two segments, with an INS precise enough that
// linking them is a test of the mechanism rather than of the INS.
SimulationConfig blankableConfig() {
  SimulationConfig config = *simulationPreset("tiny");
  config.name = "tiny-blanked";
  config.motion.length_m = 2.4;
  config.ins.rate_hz = 5.0;
  config.ins.horizontal_noise_m = 0.002;
  config.ins.horizontal_drift_m_per_sqrt_s = 0.0;
  config.ins.depth_noise_m = 0.002;
  config.ins.depth_drift_m_per_sqrt_s = 0.0;
  return config;
}

TEST(FrontendEndToEnd, BlackFramesAreOneReportedLossAndTheFramesAfterArePosedInTheSameFrame) {
  const auto source = testing::simulatedFrontendSurvey("blankable", blankableConfig());
  testing::TempFolder temp;
  const auto folder = temp.path() / "survey";
  testing::copyFolder(source, folder);
  Survey survey = loadSurvey(folder);
  const int n = survey.rgb.frameCount();
  const int first_black = n / 2 - 6, last_black = n / 2 + 5;
  const cv::Size size = survey.rgb.frameSize();
  for (int i = first_black; i <= last_black; ++i) {
    cv::imwrite(survey.rgb.framePath(i).string(), cv::Mat(size, CV_8UC3, cv::Scalar(0, 0, 0)));
  }
  survey = loadSurvey(folder);
  const FrontendResult result = runFrontend(survey, FrontendOptions{});
  std::cout << result.summary() << "\n";
  ASSERT_EQ(result.losses.size(), 1u);
  EXPECT_EQ(result.losses[0].first_frame, first_black);
  EXPECT_EQ(result.losses[0].last_frame, last_black);
  EXPECT_NE(result.losses[0].reason.find("dark"), std::string::npos) << result.losses[0].reason;
  for (const FrameRecord& f : result.frames) {
    const bool black = f.index >= first_black && f.index <= last_black;
    EXPECT_EQ(f.posed, !black) << "frame " << f.index;
    if (black) EXPECT_EQ(f.status, FrameStatus::no_texture);
  }
  ASSERT_EQ(result.segments.size(), 2u);
  EXPECT_TRUE(result.segments[0].reference);
  EXPECT_TRUE(result.segments[1].linked);
  // 12 black frames (0.5 s): the seabed after them overlaps the one before,
  // so the segments are joined by vision, not through the INS.
  EXPECT_EQ(result.segments[1].link, SegmentLink::vision) << result.segments[1].note;
  EXPECT_GT(result.segments[1].first_frame, last_black);
  // The second segment's observations too, mapped into the linked map.
  expectFrameObservationsFitTheirFrames(result, survey, FrontendOptions{});

  // Both sides of the gap in one frame: one Sim(3) fits them all.
  const auto truth = readTruthPoses(folder / "truth" / "rgb_poses.csv");
  const testing::AlignedError error = testing::alignedFrameError(result, truth);
  std::cout << "aligned rms " << error.rms_m << " m over a " << error.path_length_m << " m path ("
            << error.percentOfPath() << " %)\n";
  EXPECT_LE(error.percentOfPath(), 1.0);
}

TEST(FrontendEndToEnd, UndecodableFrameIsReportedByIndexAndFileNotSilentlySkipped) {
  const auto source = testing::simulatedFrontendSurvey("tiny", *simulationPreset("tiny"));
  testing::TempFolder temp;
  const auto folder = temp.path() / "survey";
  testing::copyFolder(source, folder);
  Survey survey = loadSurvey(folder);
  const int broken = survey.rgb.frameCount() / 2;
  testing::writeText(survey.rgb.framePath(broken), "not a PNG");
  const FrontendResult result = runFrontend(survey, FrontendOptions{});
  const FrameRecord& frame = result.frames.at(std::size_t(broken));
  EXPECT_FALSE(frame.posed);
  EXPECT_EQ(frame.status, FrameStatus::undecodable);
  ASSERT_EQ(result.losses.size(), 1u);
  EXPECT_EQ(result.losses[0].first_frame, broken);
  EXPECT_EQ(result.losses[0].last_frame, broken);
  EXPECT_NE(result.losses[0].reason.find(survey.rgb.framePath(broken).filename().string()), std::string::npos)
      << result.losses[0].reason;
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_NE(result.warnings[0].find("frame " + std::to_string(broken)), std::string::npos);
  // One bad frame is bridged: the same segment goes on after it.
  EXPECT_EQ(result.segments.size(), 1u);
  EXPECT_EQ(result.posedFrameCount(), survey.rgb.frameCount() - 1);
}

TEST(FrontendEndToEnd, AVideoThatNeverInitialisesEndsWithAnErrorNamingTheFramesTried) {
  const auto source = testing::simulatedFrontendSurvey("tiny", *simulationPreset("tiny"));
  const Survey survey = loadSurvey(source);
  FrontendOptions options;
  options.last_frame = 3;  // four frames: far too little parallax
  try {
    runFrontend(survey, options);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("never initialised on frames 0-3"), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace hsmap
