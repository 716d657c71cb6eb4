// Ground truth of a simulated survey (the `tiny` preset), checked against
// what was rendered: the survey loads like any other, the UHI poses are the
// camera trajectory shifted by d and moved by T_C_U, scene points projected
// with the true poses land where the RGB frames show them, the UHI cube shows
// the true reflectance where the true poses say it looks, and the truth
// reflectance raster is the material field of the scene.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <numeric>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/so3.h"
#include "core/geometry/local_ned_frame.h"
#include "core/io/envi_reader.h"
#include "core/io/ply_io.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/survey.h"
#include "core/survey/survey_truth.h"
#include "pipelines/simulate/scene/material_field.h"
#include "tests/pipelines/simulate/tiny_survey.h"

namespace hsmap {
namespace {

testing::TinySurveyCleanup cleanup;

SE3d toSe3(const RigidTransformConfig& transform) {
  return SE3d(transform.rotation, transform.translation_m);
}

// T_W_C at time t, interpolated between the RGB frames' true poses (linear in
// translation, slerp in rotation: at 25 Hz and ROV speeds this is exact to
// micrometres, far below the 4.5 mm that a 15 ms time offset moves the camera).
SE3d interpolatePose(const std::vector<TruthPose>& poses, double t) {
  const auto after = std::upper_bound(poses.begin(), poses.end(), t,
                                      [](double time, const TruthPose& p) { return time < p.t; });
  if (after == poses.begin() || after == poses.end()) {
    throw std::out_of_range("time outside the frames");
  }
  const TruthPose& a = *(after - 1);
  const TruthPose& b = *after;
  const double w = (t - a.t) / (b.t - a.t);
  return SE3d(a.T_W_X.q.slerp(w, b.T_W_X.q), (1.0 - w) * a.T_W_X.t + w * b.T_W_X.t);
}

TEST(SimulatedSurvey, LoadsThroughTheSurveyLoaderWithEveryTruthFile) {
  const auto& tiny = testing::tinySurvey();
  const Survey survey = loadSurvey(tiny.folder);
  EXPECT_EQ(survey.rgb.frameCount(), tiny.summary.rgb_frames);
  EXPECT_EQ(survey.cube->lines(), tiny.summary.uhi_lines);
  EXPECT_EQ(survey.cube->samples(), tiny.config.uhi.camera.samples);
  EXPECT_EQ(survey.cube->bands(), tiny.config.uhi.bands);
  EXPECT_EQ(int(survey.ins.fixes.size()), tiny.summary.ins_fixes);
  EXPECT_TRUE(survey.ins.has_attitude);
  EXPECT_TRUE(survey.origin_from_config);
  EXPECT_TRUE(survey.truth.present);
  EXPECT_TRUE(survey.truth.missing_files.empty());
  const SurveyTruth truth = loadSurveyTruth(tiny.folder);
  EXPECT_EQ(truth.rgb_poses.size(), std::size_t(tiny.summary.rgb_frames));
  EXPECT_EQ(truth.uhi_poses.size(), std::size_t(tiny.summary.uhi_lines));
  EXPECT_EQ(truth.calibration.water_attenuation_per_m.size(), std::size_t(tiny.config.uhi.bands));
  // The INS covers both sensors.
  EXPECT_LE(survey.ins.fixes.front().t, std::min(survey.rgb.time(0), survey.line_times.front()));
  EXPECT_GE(survey.ins.fixes.back().t,
            std::max(survey.rgb.time(survey.rgb.frameCount() - 1), survey.line_times.back()));
}

TEST(SimulatedSurvey, SurveyYamlHoldsTheConfiguredCalibrationErrors) {
  const auto& tiny = testing::tinySurvey();
  const Survey survey = loadSurvey(tiny.folder);
  const SurveyTruth truth = loadSurveyTruth(tiny.folder);
  const SE3d guess = toSe3(survey.config.uhi.T_C_U);
  const SE3d exact = toSe3(truth.calibration.T_C_U);
  const double angle_deg =
      2.0 * std::asin(std::min(1.0, (guess.q.inverse() * exact.q).vec().norm())) * 180.0 / M_PI;
  EXPECT_NEAR(angle_deg, tiny.config.calibration.error_rotation_deg, 1e-6);
  EXPECT_NEAR((guess.t - exact.t).norm(), tiny.config.calibration.error_translation_m, 1e-9);
  EXPECT_NEAR(truth.calibration.time_offset_s - survey.config.uhi.time_offset_s,
              tiny.config.calibration.error_time_offset_s, 1e-12);
  // The lever arm is exact in synthetic surveys.
  EXPECT_TRUE(survey.config.ins.T_B_C.translation_m.isApprox(truth.calibration.T_B_C.translation_m));
}

TEST(SimulatedSurvey, UhiPosesAreTheCameraTrajectoryAtTheTrueTimeTimesTheExtrinsic) {
  const auto& tiny = testing::tinySurvey();
  const Survey survey = loadSurvey(tiny.folder);
  const SurveyTruth truth = loadSurveyTruth(tiny.folder);
  const SE3d T_C_U = toSe3(truth.calibration.T_C_U);
  const double d = truth.calibration.time_offset_s;
  ASSERT_GT(std::abs(d), 0.005);
  double worst_position = 0.0, worst_angle = 0.0, worst_if_d_ignored = 1e9;
  int checked = 0;
  for (const TruthLinePose& line : truth.uhi_poses) {
    EXPECT_DOUBLE_EQ(line.t, survey.line_times[line.line] + d);
    if (line.t <= truth.rgb_poses.front().t || line.t >= truth.rgb_poses.back().t) continue;
    const SE3d expected = interpolatePose(truth.rgb_poses, line.t) * T_C_U;
    worst_position = std::max(worst_position, (expected.t - line.T_W_U.t).norm());
    worst_angle = std::max(worst_angle, expected.q.angularDistance(line.T_W_U.q));
    const double recorded = survey.line_times[line.line];
    if (recorded > truth.rgb_poses.front().t && recorded < truth.rgb_poses.back().t) {
      const SE3d at_recorded = interpolatePose(truth.rgb_poses, recorded) * T_C_U;
      worst_if_d_ignored = std::min(worst_if_d_ignored, (at_recorded.t - line.T_W_U.t).norm());
    }
    ++checked;
  }
  EXPECT_GT(checked, tiny.summary.uhi_lines - 4);
  EXPECT_LT(worst_position, 2e-5);               // metres
  EXPECT_LT(worst_angle, 1e-5);                  // radians
  EXPECT_GT(worst_if_d_ignored, 100 * 2e-5);     // the test can tell d from no d
}

// Corners of one frame, cast onto the true scene with the true pose and
// projected into a later frame with its true pose, land where optical flow
// finds them in the rendered images.
TEST(SimulatedSurvey, SceneProjectedWithTruePosesLandsOnTheRenderedFrames) {
  const auto& tiny = testing::tinySurvey();
  const SurveyTruth truth = loadSurveyTruth(tiny.folder);
  const Survey survey = loadSurvey(tiny.folder);
  const PlyMesh scene = readPly(truth.scene_path);
  const MeshRayCaster caster(scene.vertices, scene.triangles);
  const PinholeRadtanCamera camera(truth.calibration.rgb_camera);
  const int first = 10, second = 16;  // 0.24 s apart: ~7 cm of motion
  const cv::Mat image_a = survey.rgb.frame(first);
  const cv::Mat image_b = survey.rgb.frame(second);
  cv::Mat grey_a, grey_b;
  cv::cvtColor(image_a, grey_a, cv::COLOR_BGR2GRAY);
  cv::cvtColor(image_b, grey_b, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(grey_a, corners, 400, 0.01, 8);
  ASSERT_GE(corners.size(), 100u);
  std::vector<cv::Point2f> tracked;
  std::vector<unsigned char> status;
  std::vector<float> errors;
  cv::calcOpticalFlowPyrLK(grey_a, grey_b, corners, tracked, status, errors, cv::Size(21, 21), 3);
  // Forward-backward check: a track that does not come back to its corner is
  // a tracker failure, not a statement about the truth.
  std::vector<cv::Point2f> back;
  std::vector<unsigned char> back_status;
  cv::calcOpticalFlowPyrLK(grey_b, grey_a, tracked, back, back_status, errors, cv::Size(21, 21), 3);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    if (!back_status[i] || cv::norm(back[i] - corners[i]) > 0.3) status[i] = 0;
  }
  const SE3d& T_W_A = truth.rgb_poses[first].T_W_X;
  const SE3d& T_W_B = truth.rgb_poses[second].T_W_X;
  std::vector<double> residuals;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    if (!status[i]) continue;
    const auto ray_C = camera.unproject(Eigen::Vector2d(corners[i].x, corners[i].y));
    if (!ray_C) continue;
    const Ray ray{T_W_A.t, (T_W_A.q * *ray_C).normalized()};
    const RayHit hit = caster.intersect(ray);
    if (!hit.hit()) continue;
    const Eigen::Vector3d p_W = ray.origin + hit.distance * ray.direction;
    const Eigen::Vector3d p_B = T_W_B.inverse() * p_W;
    if (p_B.z() <= 0.0) continue;
    // Skip points hidden from the second camera.
    const Eigen::Vector3d to_point = p_W - T_W_B.t;
    const RayHit seen = caster.intersect(Ray{T_W_B.t, to_point.normalized()});
    if (!seen.hit() || seen.distance < to_point.norm() - 1e-3) continue;
    const Eigen::Vector2d predicted = camera.project(p_B);
    constexpr double kBorder = 12.0;  // the tracking window must stay inside the image
    if (predicted.x() < kBorder || predicted.y() < kBorder ||
        predicted.x() > camera.width() - kBorder || predicted.y() > camera.height() - kBorder) {
      continue;
    }
    residuals.push_back(
        (predicted - Eigen::Vector2d(tracked[i].x, tracked[i].y)).norm());
  }
  ASSERT_GE(residuals.size(), 80u);
  std::sort(residuals.begin(), residuals.end());
  const double median = residuals[residuals.size() / 2];
  const double p90 = residuals[residuals.size() * 9 / 10];
  EXPECT_LT(median, 0.25) << "pixels";
  EXPECT_LT(p90, 0.8) << "pixels; median " << median << ", " << residuals.size() << " points";
}

// Along each scan line, the band near 550 nm follows the true reflectance of
// the surface points the true pose says the pixels see: the lighting varies
// smoothly across the swath, the texture does not, so after dividing out a
// smooth trend the two correlate strongly, and much less when the true points
// are shifted by a few pixels.
TEST(SimulatedSurvey, UhiCubeShowsTheTrueReflectanceWhereTheTruePosesLook) {
  const auto& tiny = testing::tinySurvey();
  const SurveyTruth truth = loadSurveyTruth(tiny.folder);
  const Survey survey = loadSurvey(tiny.folder);
  const PlyMesh scene = readPly(truth.scene_path);
  const MeshRayCaster caster(scene.vertices, scene.triangles);
  const PushbroomCamera camera(truth.calibration.uhi_camera);
  const int band = int(std::min_element(survey.wavelengths_nm.begin(), survey.wavelengths_nm.end(),
                                        [](double a, double b) {
                                          return std::abs(a - 550.0) < std::abs(b - 550.0);
                                        }) -
                       survey.wavelengths_nm.begin());
  // The true reflectance at a surface point: the scene's material field (the
  // tiny preset's seabed has no rocks).
  const MaterialField materials(simulationMaterialSeed(tiny.config));
  const Eigen::RowVectorXf endmembers =
      MaterialField::endmemberMatrix({survey.wavelengths_nm[band]}).row(0);
  auto trueReflectance = [&](const Eigen::Vector3d& p_W) {
    const Abundances a = materials.abundances(p_W, SurfaceKind::seabed);
    return double(endmembers * Eigen::Map<const Eigen::Matrix<float, kEndmemberCount, 1>>(a.data()));
  };
  auto correlation = [](const std::vector<double>& x, const std::vector<double>& y) {
    const double n = double(x.size());
    const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n;
    const double my = std::accumulate(y.begin(), y.end(), 0.0) / n;
    double sxy = 0, sxx = 0, syy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      sxy += (x[i] - mx) * (y[i] - my);
      sxx += (x[i] - mx) * (x[i] - mx);
      syy += (y[i] - my) * (y[i] - my);
    }
    return sxy / std::sqrt(sxx * syy);
  };
  std::vector<double> aligned, shifted;
  std::vector<int> best_shifts;
  Eigen::MatrixXf cube_line;
  for (int j = 5; j < survey.cube->lines() - 5; j += 10) {
    survey.cube->readLine(j, cube_line);
    const SE3d& T_W_U = truth.uhi_poses[j].T_W_U;
    std::vector<double> rho;
    for (int s = 0; s < camera.samples(); ++s) {
      const auto ray_U = camera.unproject(double(s));
      const Eigen::Vector3d direction = (T_W_U.q * *ray_U).normalized();
      const RayHit hit = caster.intersect(Ray{T_W_U.t, direction});
      rho.push_back(hit.hit() ? trueReflectance(T_W_U.t + hit.distance * direction)
                              : std::numeric_limits<double>::quiet_NaN());
    }
    // DN / rho is the lighting, smooth across the swath: divide the DN by its
    // running mean over +-15 pixels, then correlate with the true reflectance
    // of the pixel `shift` samples away.
    const int half = 15, max_shift = 8;
    std::vector<double> x;
    std::vector<int> valid_s;
    for (int s = half + max_shift; s < camera.samples() - half - max_shift; ++s) {
      double dn_sum = 0.0, rho_sum = 0.0;
      bool valid = true;
      for (int k = -half - max_shift; k <= half + max_shift; ++k) {
        valid = valid && std::isfinite(rho[s + k]);
      }
      if (!valid) continue;
      for (int k = -half; k <= half; ++k) {
        dn_sum += cube_line(band, s + k);
        rho_sum += rho[s + k];
      }
      x.push_back(cube_line(band, s) / (dn_sum / rho_sum));
      valid_s.push_back(s);
    }
    if (x.size() < 100) continue;
    int best_shift = 0;
    double best = -2.0;
    for (int shift = -max_shift; shift <= max_shift; ++shift) {
      std::vector<double> y;
      for (int s : valid_s) y.push_back(rho[s + shift]);
      const double r = correlation(x, y);
      if (shift == 0) aligned.push_back(r);
      if (std::abs(shift) == 2) shifted.push_back(r);
      if (r > best) best = r, best_shift = shift;
    }
    best_shifts.push_back(best_shift);
  }
  ASSERT_GE(aligned.size(), 5u);
  std::sort(aligned.begin(), aligned.end());
  std::sort(shifted.begin(), shifted.end());
  EXPECT_GT(aligned[aligned.size() / 2], 0.9);
  EXPECT_LT(shifted[shifted.size() / 2], aligned[aligned.size() / 2] - 0.1);
  // The pixel the true pose names is the best match on (nearly) every line.
  const auto exact = std::count(best_shifts.begin(), best_shifts.end(), 0);
  EXPECT_GE(double(exact), 0.9 * double(best_shifts.size()));
}

// The truth raster is north-up with the map info's corner: each valid pixel
// holds the material field's reflectance at the top of the scene below its
// centre, and the footprint is the UHI's swath.
TEST(SimulatedSurvey, TruthReflectanceIsTheMaterialFieldOverTheSwath) {
  const auto& tiny = testing::tinySurvey();
  const SurveyTruth truth = loadSurveyTruth(tiny.folder);
  const PlyMesh scene = readPly(truth.scene_path);
  const MeshRayCaster caster(scene.vertices, scene.triangles);
  const EnviReader reflectance(truth.reflectance_header_path);
  const EnviHeader& header = reflectance.header();
  ASSERT_TRUE(header.map_info.has_value());
  EXPECT_EQ(header.map_info->projection, "Arbitrary");
  EXPECT_EQ(header.data_type, EnviDataType::float32);
  EXPECT_EQ(header.bands, tiny.config.uhi.bands);
  const Eigen::MatrixXf endmembers = MaterialField::endmemberMatrix(header.wavelength);
  ASSERT_EQ(endmembers.rows(), header.bands);
  // The scene's seabed and rock kinds are not in the PLY; on the tiny preset's
  // low-relief seabed every triangle is seabed.
  const MaterialField materials(simulationMaterialSeed(tiny.config));
  Eigen::MatrixXf row_values;
  int valid = 0, checked = 0;
  const double px = header.map_info->pixel_size_x;
  for (int r = 0; r < reflectance.lines(); r += 7) {
    reflectance.readLine(r, row_values);
    for (int c = 0; c < reflectance.samples(); c += 5) {
      if (!std::isfinite(row_values(0, c))) continue;
      ++valid;
      const double north = header.map_info->northing - (r + 0.5) * px;
      const double east = header.map_info->easting + (c + 0.5) * px;
      const Ray down{Eigen::Vector3d(north, east, caster.bounds().min().z() - 1.0),
                     Eigen::Vector3d::UnitZ()};
      const RayHit hit = caster.intersect(down);
      ASSERT_TRUE(hit.hit());
      const Abundances a =
          materials.abundances(down.origin + hit.distance * down.direction, SurfaceKind::seabed);
      const Eigen::VectorXf expected =
          endmembers * Eigen::Map<const Eigen::Matrix<float, kEndmemberCount, 1>>(a.data());
      EXPECT_LT((row_values.col(c) - expected).cwiseAbs().maxCoeff(), 1e-5f)
          << "row " << r << " col " << c;
      ++checked;
    }
  }
  EXPECT_GT(checked, 200);
  // The swath of the tiny preset: ~1.2 m of track x ~1.9 m across at 1.5 m altitude.
  const double area = double(tiny.summary.reflectance_valid_pixels) * px * px;
  const double swath_width = 2.0 * tiny.config.motion.altitude_m *
                             (tiny.config.uhi.camera.samples / 2.0) / tiny.config.uhi.camera.f;
  const double track = tiny.config.motion.speed_m_s * tiny.summary.survey_seconds;
  EXPECT_NEAR(area, swath_width * track, 0.25 * swath_width * track);
}

// The INS fixes are the body pose of the truth (T_W_C T_B_C^-1) plus noise
// and drift of the configured size.
TEST(SimulatedSurvey, InsFixesAreTheTrueBodyPoseWithinTheConfiguredNoise) {
  const auto& tiny = testing::tinySurvey();
  const Survey survey = loadSurvey(tiny.folder);
  const SurveyTruth truth = loadSurveyTruth(tiny.folder);
  const LocalNedFrame w_frame(survey.origin);
  const SE3d T_C_B = toSe3(truth.calibration.T_B_C).inverse();
  const InsNoiseConfig& noise = tiny.config.ins;
  const double span = survey.ins.fixes.back().t - survey.ins.fixes.front().t;
  const double horizontal_sigma = std::hypot(
      noise.horizontal_noise_m, noise.horizontal_drift_m_per_sqrt_s * std::sqrt(span));
  const double depth_sigma =
      std::hypot(noise.depth_noise_m, noise.depth_drift_m_per_sqrt_s * std::sqrt(span));
  int compared = 0;
  for (const InsFix& fix : survey.ins.fixes) {
    if (fix.t <= truth.rgb_poses.front().t || fix.t >= truth.rgb_poses.back().t) continue;
    const SE3d T_W_B = interpolatePose(truth.rgb_poses, fix.t) * T_C_B;
    const Eigen::Vector3d p_W = w_frame.toNed({fix.lat_deg, fix.lon_deg, fix.depth_m});
    EXPECT_LT((p_W - T_W_B.t).head<2>().norm(), 5.0 * horizontal_sigma) << "t " << fix.t;
    EXPECT_LT(std::abs(p_W.z() - T_W_B.t.z()), 5.0 * depth_sigma) << "t " << fix.t;
    const Eigen::Quaterniond q_W_B =
        quaternionFromRollPitchHeadingDeg(fix.roll_deg, fix.pitch_deg, fix.heading_deg);
    EXPECT_LT(q_W_B.angularDistance(T_W_B.q) * 180.0 / M_PI,
              5.0 * (noise.heading_noise_deg + noise.roll_pitch_noise_deg))
        << "t " << fix.t;
    ++compared;
  }
  EXPECT_GE(compared, 1);
}

TEST(SimulatedSurvey, SameConfigurationWritesTheSameBytes) {
  const auto& tiny = testing::tinySurvey();
  const std::filesystem::path again = tiny.folder.string() + "_again";
  std::ostringstream log;
  simulateSurvey(tiny.config, again, log);
  int compared = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(tiny.folder)) {
    if (!entry.is_regular_file()) continue;
    const auto relative = std::filesystem::relative(entry.path(), tiny.folder);
    std::ifstream a(entry.path(), std::ios::binary), b(again / relative, std::ios::binary);
    ASSERT_TRUE(b.good()) << relative;
    const std::string bytes_a((std::istreambuf_iterator<char>(a)), {});
    const std::string bytes_b((std::istreambuf_iterator<char>(b)), {});
    EXPECT_TRUE(bytes_a == bytes_b) << relative;
    ++compared;
  }
  EXPECT_GT(compared, 50);
  std::filesystem::remove_all(again);
}

}  // namespace
}  // namespace hsmap
