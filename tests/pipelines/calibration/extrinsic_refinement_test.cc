#include "pipelines/calibration/extrinsic_refinement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <random>

#include "core/geometry/pose_interpolation.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/so3.h"
#include "core/io/envi_writer.h"
#include "core/io/ply_io.h"
#include "tests/support/temp_folder.h"
#include "tests/support/uhi_camera.h"

namespace hsmap {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

PushbroomParameters uhiCamera() { return testing::presetUhiCamera(); }

// Rugged terrain below the vehicle: W is North-East-Down, the seabed's depth
// varies by +-0.4 m so that the lever arm and the rotation are told apart.
double seabedDepth(double north, double east) {
  return 2.0 + 0.25 * std::sin(3.0 * north) + 0.15 * std::cos(4.0 * east) + 0.1 * east;
}

// RGB camera looking down (z_C = down), moving north 1 cm per line with a
// little wobble.
SE3d cameraPose(double line) {
  const Eigen::Vector3d wobble(0.02 * std::sin(0.05 * line), 0.015 * std::cos(0.03 * line), 0.0);
  return SE3d(expSO3(wobble), Eigen::Vector3d(0.01 * line, 0.05 * std::sin(0.02 * line), 0.0));
}

// The true extrinsic: the UHI's line (x_U) across track, as in the surveys.
SE3d trueExtrinsic() {
  return SE3d(expSO3(Eigen::Vector3d(0.0, 0.0, std::numbers::pi / 2)) *
                  expSO3(Eigen::Vector3d(0.014, -0.009, 0.021)),
              Eigen::Vector3d(0.02, 0.12, 0.01));
}

// The extrinsic guess: 2 deg and 5 cm off.
SE3d guessedExtrinsic() {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  return SE3d(trueExtrinsic().q * expSO3(Eigen::Vector3d(2.0 * kDeg * axis)),
              trueExtrinsic().t + Eigen::Vector3d(0.03, -0.03, 0.025));
}

// Where the ray of `sample` from the UHI at T_W_U meets the seabed.
Eigen::Vector3d seabedPointSeenFrom(const SE3d& T_W_U, double sample) {
  const PushbroomCamera camera(uhiCamera());
  const Eigen::Vector3d ray_W = T_W_U.q * *camera.unproject(sample);
  double s = 2.0;
  for (int i = 0; i < 50; ++i) {  // fixed point on the depth along the ray
    const Eigen::Vector3d p = T_W_U.t + s * ray_W;
    s += (seabedDepth(p.x(), p.y()) - p.z()) / ray_W.z();
  }
  return T_W_U.t + s * ray_W;
}

// Where the ray of (line, sample) meets the seabed under the true extrinsic.
Eigen::Vector3d seenPoint(int line, double sample) {
  return seabedPointSeenFrom(cameraPose(line) * trueExtrinsic(), sample);
}

// The run's line poses, made with the guess: T_W_U = T_W_C T_C_U_guess.
std::vector<LinePose> runLinePoses(int lines) {
  std::vector<LinePose> poses;
  for (int k = 0; k < lines; ++k)
    poses.push_back({k, 0.01 * k, cameraPose(k) * guessedExtrinsic()});
  return poses;
}

std::vector<ExtrinsicTiePoint> tiePoints(int count, double sample_noise_px, std::mt19937& rng) {
  std::uniform_int_distribution<int> line(0, 399);
  std::uniform_real_distribution<double> sample(100.0, 1820.0);
  std::normal_distribution<double> noise(0.0, sample_noise_px);
  std::vector<ExtrinsicTiePoint> ties;
  for (int i = 0; i < count; ++i) {
    ExtrinsicTiePoint tie;
    tie.line = line(rng);
    tie.line_position = double(tie.line);
    const double u = sample(rng);
    tie.p_W = seenPoint(int(tie.line), u);
    tie.sample = u + noise(rng);
    tie.range_m = 2.0;
    ties.push_back(tie);
  }
  return ties;
}

ExtrinsicPrior surveyPrior() { return {guessedExtrinsic(), 2.0, 0.05}; }

double rotationErrorDeg(const SE3d& a, const SE3d& b) {
  return logSO3(Eigen::Quaterniond(a.q.conjugate() * b.q)).norm() / kDeg;
}

TEST(ExtrinsicRefinement, RecoversAKnownExtrinsicErrorFromTiePoints) {
  std::mt19937 rng(5);
  const std::vector<ExtrinsicTiePoint> ties = tiePoints(400, 0.5, rng);
  ASSERT_GT(rotationErrorDeg(guessedExtrinsic(), trueExtrinsic()), 1.9);
  ASSERT_GT((guessedExtrinsic().t - trueExtrinsic().t).norm(), 0.049);

  // The noise model matches the simulated noise: 0.5 px at 2 m is 0.67 mm on the ground.
  ExtrinsicRefinementOptions options;
  options.sigma_match_m = 0.5 * 2.0 / 1500.0;
  const ExtrinsicRefinementResult result = refineExtrinsicFromTiePoints(
      ties, runLinePoses(400), guessedExtrinsic(), uhiCamera(), surveyPrior(), options);
  ASSERT_TRUE(result.refined) << result.summary();
  // 2 deg / 5 cm off -> within 0.02 deg and 3 mm (0.5 px noise, 400 ties).
  EXPECT_LT(rotationErrorDeg(result.T_C_U, trueExtrinsic()), 0.02) << result.summary();
  EXPECT_LT((result.T_C_U.t - trueExtrinsic().t).norm(), 0.003) << result.summary();
  EXPECT_EQ(result.inliers + result.outliers, 400);
  EXPECT_LT(result.outliers, 8);  // Cauchy scale 3: ~1 % of Gaussian inliers beyond it
  EXPECT_GT(result.rms_u_before_px, 20.0);
  EXPECT_LT(result.rms_u_after_px, 1.0);
  EXPECT_LT(result.rms_across_after_px, 1.0);
  // The reported 1-sigma is small and the error is within a few of it.
  ASSERT_TRUE(result.sigma_rotation_deg && result.sigma_translation_m);
  EXPECT_LT(result.sigma_rotation_deg->maxCoeff(), 0.02);
  EXPECT_LT(result.sigma_translation_m->maxCoeff(), 0.003);
  EXPECT_GT(result.sigma_translation_m->minCoeff(), 0.0);
  const Eigen::Vector3d t_error = result.T_C_U.t - trueExtrinsic().t;
  for (int i = 0; i < 3; ++i)
    EXPECT_LT(std::abs(t_error[i]), 4.0 * (*result.sigma_translation_m)[i]);
  EXPECT_NE(result.summary().find("inliers"), std::string::npos);
}

// The survey's time offset guess 15 ms (1.5 lines) off: every line is
// posed where the camera was 1.5 lines later. The refinement keeps d, so
// T_C_U absorbs the shift; its 1-sigma must cover that when it is told d's
// own 1-sigma, and does not without it (the premise).
TEST(ExtrinsicRefinement, TheOneSigmaIncludesWhatTheTimeOffsetsUncertaintyMovesTheExtrinsicBy) {
  std::mt19937 rng(7);
  const std::vector<ExtrinsicTiePoint> ties = tiePoints(400, 0.5, rng);
  std::vector<LinePose> late_lines;
  for (int k = 0; k < 400; ++k) late_lines.push_back({k, 0.01 * k, cameraPose(k + 1.5) * guessedExtrinsic()});
  ExtrinsicRefinementOptions options;
  options.sigma_match_m = 0.5 * 2.0 / 1500.0;
  auto largestErrorOverSigma = [&](const ExtrinsicRefinementResult& result) {
    const Eigen::Vector3d rotation_deg =
        logSO3(Eigen::Quaterniond(trueExtrinsic().q.conjugate() * result.T_C_U.q)) / kDeg;
    const Eigen::Vector3d translation = result.T_C_U.t - trueExtrinsic().t;
    return std::max((rotation_deg.cwiseAbs().array() / result.sigma_rotation_deg->array()).maxCoeff(),
                    (translation.cwiseAbs().array() / result.sigma_translation_m->array()).maxCoeff());
  };

  ExtrinsicPrior exact_times = surveyPrior();
  exact_times.time_offset_sigma_s = 0.0;
  const ExtrinsicRefinementResult without =
      refineExtrinsicFromTiePoints(ties, late_lines, guessedExtrinsic(), uhiCamera(), exact_times, options);
  ASSERT_TRUE(without.refined && without.sigma_rotation_deg && without.sigma_translation_m) << without.summary();
  EXPECT_FALSE(without.translation_per_time_offset_m_s.has_value());
  EXPECT_GT(largestErrorOverSigma(without), 5.0) << without.summary();

  ExtrinsicPrior uncertain_times = surveyPrior();
  uncertain_times.time_offset_sigma_s = 0.02;
  const ExtrinsicRefinementResult with =
      refineExtrinsicFromTiePoints(ties, late_lines, guessedExtrinsic(), uhiCamera(), uncertain_times, options);
  ASSERT_TRUE(with.refined && with.sigma_rotation_deg && with.sigma_translation_m) << with.summary();
  ASSERT_TRUE(with.translation_per_time_offset_m_s.has_value()) << with.summary();
  // The sensitivity predicts how far the 15 ms moved the solution from the
  // one with the lines on time.
  std::vector<LinePose> on_time_lines;
  for (int k = 0; k < 400; ++k) on_time_lines.push_back({k, 0.01 * k, cameraPose(k) * guessedExtrinsic()});
  const ExtrinsicRefinementResult on_time =
      refineExtrinsicFromTiePoints(ties, on_time_lines, guessedExtrinsic(), uhiCamera(), uncertain_times, options);
  ASSERT_TRUE(on_time.refined) << on_time.summary();
  const Eigen::Vector3d moved = with.T_C_U.t - on_time.T_C_U.t;
  const Eigen::Vector3d predicted = *with.translation_per_time_offset_m_s * 0.015;
  EXPECT_GT(moved.norm(), 0.01);
  EXPECT_LT((moved - predicted).norm(), 0.25 * moved.norm()) << moved.transpose() << " / " << predicted.transpose();
  EXPECT_LT(largestErrorOverSigma(with), 3.0) << with.summary();
  EXPECT_NE(with.summary().find("per ms of the time offset"), std::string::npos);
  // Same solution either way: only the stated uncertainty differs.
  EXPECT_LT(rotationErrorDeg(with.T_C_U, without.T_C_U), 1e-9);
}

TEST(ExtrinsicRefinement, WithoutTiePointsKeepsTheExtrinsicAndSaysSo) {
  const ExtrinsicRefinementResult result = refineExtrinsicFromTiePoints(
      {}, runLinePoses(10), guessedExtrinsic(), uhiCamera(), surveyPrior());
  EXPECT_FALSE(result.refined);
  EXPECT_TRUE(result.T_C_U.q.isApprox(guessedExtrinsic().q));
  EXPECT_EQ(result.T_C_U.t, guessedExtrinsic().t);
  EXPECT_FALSE(result.sigma_rotation_deg.has_value());
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_NE(result.warnings[0].find("T_C_U kept"), std::string::npos) << result.warnings[0];
  EXPECT_NE(result.summary().find("not refined"), std::string::npos);
}

TEST(ExtrinsicRefinement, ATiePointBetweenTwoLinesIsSeenFromThePoseBetweenThem) {
  // Tie points half-way between lines (a gap-filled pixel of the ortho-image):
  // the UHI saw them from the pose interpolated between the two lines, 5 mm
  // along the track from either; taken from one of the two lines, they
  // would be off by ~2.5 px along the track.
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> line(0, 398);
  std::uniform_real_distribution<double> sample(100.0, 1820.0);
  std::vector<ExtrinsicTiePoint> ties;
  for (int i = 0; i < 300; ++i) {
    ExtrinsicTiePoint tie;
    const int below = line(rng);
    tie.line_position = below + 0.5;
    tie.line = below + 1;
    tie.sample = sample(rng);
    tie.p_W = seabedPointSeenFrom(
        interpolatePose(cameraPose(below), cameraPose(below + 1), 0.5) * trueExtrinsic(), tie.sample);
    tie.range_m = 2.0;
    ties.push_back(tie);
  }
  ExtrinsicRefinementOptions options;
  options.sigma_match_m = 0.5 * 2.0 / 1500.0;
  const ExtrinsicRefinementResult result = refineExtrinsicFromTiePoints(
      ties, runLinePoses(400), guessedExtrinsic(), uhiCamera(), surveyPrior(), options);
  ASSERT_TRUE(result.refined) << result.summary();
  EXPECT_LT(rotationErrorDeg(result.T_C_U, trueExtrinsic()), 0.01) << result.summary();
  EXPECT_LT((result.T_C_U.t - trueExtrinsic().t).norm(), 0.001) << result.summary();
  EXPECT_LT(result.rms_across_after_px, 0.05) << result.summary();
  EXPECT_EQ(result.outliers, 0);
}

TEST(ExtrinsicRefinement, TiePointsOnLinesWithoutPosesAreSkippedAndReported) {
  std::mt19937 rng(6);
  std::vector<ExtrinsicTiePoint> ties = tiePoints(3, 0.0, rng);
  for (ExtrinsicTiePoint& tie : ties) {
    tie.line += 10000;
    tie.line_position += 10000.0;
  }
  const ExtrinsicRefinementResult result = refineExtrinsicFromTiePoints(
      ties, runLinePoses(400), guessedExtrinsic(), uhiCamera(), surveyPrior());
  EXPECT_FALSE(result.refined);
  ASSERT_EQ(result.warnings.size(), 2u);
  EXPECT_NE(result.warnings[0].find("3 tie points skipped"), std::string::npos);
}

TEST(ExtrinsicRefinement, RejectsOutliers) {
  std::mt19937 rng(7);
  std::vector<ExtrinsicTiePoint> ties = tiePoints(300, 0.5, rng);
  // A fifth of the matches are wrong: their points are 5-30 cm away.
  std::uniform_real_distribution<double> offset(-0.3, 0.3);
  int wrong = 0;
  for (std::size_t i = 0; i < ties.size(); i += 5, ++wrong) {
    Eigen::Vector3d shift(offset(rng), offset(rng), 0.0);
    if (shift.norm() < 0.05) shift = Eigen::Vector3d(0.1, -0.1, 0.0);
    ties[i].p_W += shift;
  }
  const ExtrinsicRefinementResult result = refineExtrinsicFromTiePoints(
      ties, runLinePoses(400), guessedExtrinsic(), uhiCamera(), surveyPrior());
  ASSERT_TRUE(result.refined) << result.summary();
  EXPECT_GE(result.outliers, wrong - 3) << result.summary();
  EXPECT_LE(result.outliers, wrong + 6) << result.summary();
  EXPECT_EQ(std::int64_t(result.used.size()), result.inliers);
  EXPECT_LT(rotationErrorDeg(result.T_C_U, trueExtrinsic()), 0.03) << result.summary();
  EXPECT_LT((result.T_C_U.t - trueExtrinsic().t).norm(), 0.005) << result.summary();
}

// A flat textured seabed 2 half_size_m square at down 2 m, 1 cm quads whose
// vertex colours are random blobs, and the grid of 5 mm around it.
struct TexturedSeabed {
  UtmProjection projection{GeodeticPoint{43.0, 5.0, 0.0}};
  PlyMesh mesh;
  OrthoGrid grid;

  explicit TexturedSeabed(double half_size_m = 0.75) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Eigen::Vector3d> blobs;  // north, east, radius
    const double blob_reach = half_size_m + 0.05;
    const int blob_count = int(std::lround(400.0 * blob_reach * blob_reach / (0.8 * 0.8)));
    for (int i = 0; i < blob_count; ++i) {
      blobs.emplace_back(-blob_reach + 2.0 * blob_reach * unit(rng),
                         -blob_reach + 2.0 * blob_reach * unit(rng), 0.01 + 0.03 * unit(rng));
    }
    auto colour = [&](double n, double e) {
      double value = 60.0;
      for (const Eigen::Vector3d& blob : blobs) {
        const double d2 = (n - blob.x()) * (n - blob.x()) + (e - blob.y()) * (e - blob.y());
        if (d2 < 0.04) value += 150.0 * std::exp(-d2 / (2.0 * blob.z() * blob.z()));
      }
      const auto byte = std::uint8_t(std::clamp(value, 0.0, 255.0));
      return Eigen::Matrix<std::uint8_t, 3, 1>(byte, byte, std::uint8_t(byte / 2));
    };
    const int cells = int(std::lround(2.0 * half_size_m / 0.01));
    for (int i = 0; i <= cells; ++i) {
      for (int j = 0; j <= cells; ++j) {
        const double n = -half_size_m + 0.01 * i, e = -half_size_m + 0.01 * j;
        mesh.vertices.emplace_back(n, e, 2.0);
        mesh.colors.push_back(colour(n, e));
      }
    }
    for (int i = 0; i < cells; ++i) {
      for (int j = 0; j < cells; ++j) {
        const int a = i * (cells + 1) + j, b = a + 1, c = a + cells + 1, d = c + 1;
        mesh.triangles.emplace_back(a, b, d);
        mesh.triangles.emplace_back(a, d, c);
      }
    }
    Eigen::AlignedBox2d box;
    for (double n : {-half_size_m, half_size_m})
      for (double e : {-half_size_m, half_size_m}) box.extend(projection.nedToUtm({n, e, 0.0}));
    grid = OrthoGrid::coveringUtm(box, 0.005, projection.zone(), projection.northernHemisphere());
  }
};

// The seabed's RGB luminance, and a hyperspectral one: the same content
// moved by `shift` pixels, with another gain and offset, NaN where nothing
// moved in; ancillary: line = row, sample = 1000 + col, range 2 m.
struct ShiftedOrthoPair {
  cv::Mat rgb_luma, hyper_luma, ancillary;

  ShiftedOrthoPair(const TexturedSeabed& seabed, const RgbOrthoRenderer& renderer,
                   const Eigen::Vector2d& shift) {
    cv::Mat bgra;
    renderer.renderColours(0, 0, seabed.grid.cols, seabed.grid.rows, bgra);
    rgb_luma = rgbLuminance(bgra);
    const cv::Mat move = (cv::Mat_<double>(2, 3) << 1, 0, shift.x(), 0, 1, shift.y());
    cv::warpAffine(rgb_luma, hyper_luma, move, rgb_luma.size(), cv::INTER_LINEAR,
                   cv::BORDER_CONSTANT, cv::Scalar(std::numeric_limits<double>::quiet_NaN()));
    hyper_luma = 0.01 * hyper_luma + 0.2;
    ancillary = cv::Mat(rgb_luma.size(), CV_32FC4);
    for (int r = 0; r < ancillary.rows; ++r)
      for (int c = 0; c < ancillary.cols; ++c)
        ancillary.at<cv::Vec4f>(r, c) = {float(r), 1000.0f + c, 2.0f, 0.0f};
  }
};

TEST(ExtrinsicRefinement, MatchingFindsTheShiftBetweenTheOrthoImagesAndTiesTheRightPixels) {
  const TexturedSeabed seabed;
  const RgbOrthoRenderer renderer(seabed.mesh, seabed.grid, seabed.projection);
  // The hyperspectral ortho-image: the content moved by (7.3, -4.6) pixels.
  const Eigen::Vector2d shift(7.3, -4.6);
  const ShiftedOrthoPair images(seabed, renderer, shift);
  const cv::Mat& rgb_luma = images.rgb_luma;
  const cv::Mat& hyper_luma = images.hyper_luma;
  const cv::Mat& ancillary = images.ancillary;
  std::vector<ExtrinsicTiePoint> ties;
  const OrthoMatchCounts counts =
      matchOrthoImages(rgb_luma, hyper_luma, ancillary, renderer, {}, ties);
  EXPECT_GT(counts.patches, 20);
  EXPECT_GE(counts.tie_points, counts.patches * 3 / 4);
  ASSERT_EQ(std::int64_t(ties.size()), counts.tie_points);
  for (const ExtrinsicTiePoint& tie : ties) {
    EXPECT_LT((tie.hyper_col_row - tie.rgb_col_row - shift).norm(), 0.3)
        << tie.rgb_col_row.transpose();
    // The ancillary layer interpolated at the match (line = row, sample =
    // 1000 + col, continuous), and the point under the patch centre.
    EXPECT_NEAR(tie.line_position, tie.hyper_col_row.y(), 1e-3);
    EXPECT_EQ(tie.line, std::llround(tie.line_position));
    EXPECT_NEAR(tie.sample, 1000.0 + tie.hyper_col_row.x(), 1e-3);
    const Eigen::Vector2d pixel_of_point = seabed.grid.pixelOfW(tie.p_W, seabed.projection);
    EXPECT_LT((pixel_of_point - tie.rgb_col_row).norm(), 0.01);
    EXPECT_NEAR(tie.p_W.z(), 2.0, 1e-4);
    EXPECT_GT(tie.ncc, 0.9);
  }
}

// A guess of T_C_U a few degrees off moves the whole hyperspectral image by
// more than the lattice's search radius (0.15 m): the coarse step finds the
// shift and each patch is searched around it.
TEST(ExtrinsicRefinement, TheCoarseStepFindsAShiftBeyondTheSearchRadius) {
  const TexturedSeabed seabed(1.5);
  const RgbOrthoRenderer renderer(seabed.mesh, seabed.grid, seabed.projection);
  const Eigen::Vector2d shift(44.3, -35.6);  // 0.22 m and -0.18 m
  const ShiftedOrthoPair images(seabed, renderer, shift);
  ExtrinsicRefinementOptions options;
  ASSERT_GT(shift.norm() * seabed.grid.pixel_m, options.search_radius_m);

  std::vector<ExtrinsicTiePoint> ties;
  const OrthoMatchCounts counts = matchOrthoImages(images.rgb_luma, images.hyper_luma,
                                                   images.ancillary, renderer, options, ties);
  EXPECT_EQ(counts.coarse_scale, 1.0);
  EXPECT_GT(counts.coarse_matched, counts.coarse_patches / 3);
  // Patches with fewer than 3 coarse matches near them (by the empty band
  // the shift leaves) are searched around no shift and find nothing.
  EXPECT_GE(counts.shifted, counts.textured * 9 / 10);
  EXPECT_GT(counts.textured, 100);
  EXPECT_GE(counts.tie_points, counts.textured * 3 / 4);
  // Sub-pixel by parabolas: within half a pixel (2.5 mm, half the 5 mm the
  // solve assumes for a match).
  for (const ExtrinsicTiePoint& tie : ties) {
    EXPECT_LT((tie.hyper_col_row - tie.rgb_col_row - shift).norm(), 0.5)
        << tie.rgb_col_row.transpose();
    EXPECT_NEAR(tie.line_position, tie.hyper_col_row.y(), 1e-3);
  }

  // Without the coarse step the true peak lies outside every search window.
  options.coarse_pixel_m = 0.0;
  std::vector<ExtrinsicTiePoint> fine_only;
  const OrthoMatchCounts fine_counts = matchOrthoImages(
      images.rgb_luma, images.hyper_luma, images.ancillary, renderer, options, fine_only);
  EXPECT_EQ(fine_counts.coarse_patches, 0);
  EXPECT_EQ(fine_counts.shifted, 0);
  for (const ExtrinsicTiePoint& tie : fine_only) {
    EXPECT_GT((tie.hyper_col_row - tie.rgb_col_row - shift).norm(), 1.0);
  }
  EXPECT_LT(fine_counts.tie_points, counts.tie_points / 10);
}

// A swath narrower than the coarse search windows (1.2 m): none of them is
// wholly valid, so the coarse step matches again with windows of half the
// size, and still finds a shift beyond the lattice's search radius.
TEST(ExtrinsicRefinement, OnANarrowSwathTheCoarseStepUsesHalfSizeWindows) {
  const TexturedSeabed seabed(1.5);
  const RgbOrthoRenderer renderer(seabed.mesh, seabed.grid, seabed.projection);
  const Eigen::Vector2d shift(35.3, -8.4);  // 0.18 m and -0.04 m
  ShiftedOrthoPair images(seabed, renderer, shift);
  // The hyperspectral image only on a band of columns 0.9 m wide.
  const int band0 = images.hyper_luma.cols / 2 - 90, band1 = images.hyper_luma.cols / 2 + 90;
  images.hyper_luma.colRange(0, band0).setTo(std::numeric_limits<double>::quiet_NaN());
  images.hyper_luma.colRange(band1, images.hyper_luma.cols)
      .setTo(std::numeric_limits<double>::quiet_NaN());
  ExtrinsicRefinementOptions options;
  ASSERT_GT(std::abs(shift.x()) * seabed.grid.pixel_m, options.search_radius_m);

  std::vector<ExtrinsicTiePoint> ties;
  const OrthoMatchCounts counts = matchOrthoImages(images.rgb_luma, images.hyper_luma,
                                                   images.ancillary, renderer, options, ties);
  EXPECT_EQ(counts.coarse_scale, 0.5);
  EXPECT_GE(counts.coarse_matched, options.coarse_min_matches);
  EXPECT_GT(counts.tie_points, 20);
  for (const ExtrinsicTiePoint& tie : ties) {
    EXPECT_LT((tie.hyper_col_row - tie.rgb_col_row - shift).norm(), 0.5)
        << tie.rgb_col_row.transpose();
  }

  options.coarse_pixel_m = 0.0;
  std::vector<ExtrinsicTiePoint> fine_only;
  matchOrthoImages(images.rgb_luma, images.hyper_luma, images.ancillary, renderer, options,
                   fine_only);
  for (const ExtrinsicTiePoint& tie : fine_only) {
    EXPECT_GT((tie.hyper_col_row - tie.rgb_col_row - shift).norm(), 1.0);
  }
}

TEST(ExtrinsicRefinement, BlankImagesGiveNoMatches) {
  const TexturedSeabed seabed;
  const RgbOrthoRenderer renderer(seabed.mesh, seabed.grid, seabed.projection);
  const cv::Mat flat(seabed.grid.rows, seabed.grid.cols, CV_32F, cv::Scalar(0.5));
  const cv::Mat ancillary(flat.size(), CV_32FC4, cv::Scalar::all(1.0));
  std::vector<ExtrinsicTiePoint> ties;
  const OrthoMatchCounts counts = matchOrthoImages(flat, flat, ancillary, renderer, {}, ties);
  EXPECT_GT(counts.patches, 20);
  EXPECT_EQ(counts.textured, 0);
  EXPECT_TRUE(ties.empty());
}

TEST(ExtrinsicRefinement, BandCombinationFitsTheRgbResponseFromTheVisibleBands) {
  // 40 x 30 pixels, 6 bands; the "RGB camera" sees 3 b(460) + b(520) - 0.5 b(620) + 5.
  const testing::TempFolder folder;
  const std::vector<double> wavelengths{420.0, 460.0, 520.0, 560.0, 620.0, 700.0};
  EnviHeader header;
  header.samples = 30;
  header.lines = 40;
  header.bands = 6;
  header.wavelength = wavelengths;
  header.wavelength_units = "Nanometers";
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  cv::Mat rgb_luma(40, 30, CV_32F);
  {
    EnviWriter writer(folder / "ortho.hdr", header);
    Eigen::MatrixXf line(6, 30);
    for (int r = 0; r < 40; ++r) {
      for (int c = 0; c < 30; ++c) {
        for (int b = 0; b < 6; ++b) line(b, c) = unit(rng);
        if (r == 7 && c == 9) line(2, c) = std::numeric_limits<float>::quiet_NaN();
        rgb_luma.at<float>(r, c) = 3.0f * line(1, c) + line(2, c) - 0.5f * line(4, c) + 5.0f;
      }
      writer.writeLine(line);
    }
    writer.finish();
  }
  const EnviReader ortho(folder / "ortho.hdr");
  ExtrinsicRefinementOptions options;
  options.ridge = 1e-9;
  options.fit_stride_px = 1;
  const BandCombination fitted = hyperspectralLuminance(ortho, wavelengths, rgb_luma, options);
  ASSERT_TRUE(fitted.fitted);
  EXPECT_GT(fitted.r2, 0.999999);
  const std::vector<double> expected{0.0, 3.0, 1.0, 0.0, -0.5, 0.0};
  for (int b = 0; b < 6; ++b) EXPECT_NEAR(fitted.weights[b], expected[b], 1e-4) << "band " << b;
  EXPECT_NEAR(fitted.offset, 5.0, 1e-4);
  EXPECT_TRUE(std::isnan(fitted.luma.at<float>(7, 9)));
  EXPECT_NEAR(fitted.luma.at<float>(3, 4), rgb_luma.at<float>(3, 4), 1e-4);

  // Fixed weights: luminance-like, summing to one over the visible bands only.
  options.fit_band_weights = false;
  const BandCombination fixed = hyperspectralLuminance(ortho, wavelengths, rgb_luma, options);
  EXPECT_FALSE(fixed.fitted);
  EXPECT_EQ(fixed.weights[0], 0.0);
  EXPECT_EQ(fixed.weights[5], 0.0);
  double sum = 0.0;
  for (double w : fixed.weights) sum += w;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_GT(fixed.weights[2], fixed.weights[1]);  // green above blue
}

TEST(ExtrinsicRefinement, UpdatedLinePosesUseTheNewExtrinsic) {
  const std::vector<LinePose> run = runLinePoses(5);
  const std::vector<LinePose> updated = updatedLinePoses(run, guessedExtrinsic(), trueExtrinsic());
  ASSERT_EQ(updated.size(), run.size());
  for (int k = 0; k < 5; ++k) {
    const SE3d expected = cameraPose(k) * trueExtrinsic();
    EXPECT_EQ(updated[k].line, run[k].line);
    EXPECT_EQ(updated[k].t, run[k].t);
    EXPECT_LT((updated[k].T.t - expected.t).norm(), 1e-12);
    EXPECT_LT(rotationErrorDeg(updated[k].T, expected), 1e-9);
  }
}

TEST(ExtrinsicRefinement, GridFromTheHeaderMapInfoIsTheWrittenGrid) {
  OrthoGrid grid;
  grid.pixel_m = 0.005;
  grid.west_m = 663017.08;
  grid.north_m = 4762775.66;
  grid.cols = 728;
  grid.rows = 3902;
  grid.zone = 31;
  grid.northern = true;
  EnviHeader header;
  header.samples = grid.cols;
  header.lines = grid.rows;
  header.bands = 1;
  header.map_info = grid.mapInfo();
  const OrthoGrid back = orthoGridFromHeader(header);
  EXPECT_EQ(back.cols, grid.cols);
  EXPECT_EQ(back.rows, grid.rows);
  EXPECT_DOUBLE_EQ(back.west_m, grid.west_m);
  EXPECT_DOUBLE_EQ(back.north_m, grid.north_m);
  EXPECT_DOUBLE_EQ(back.pixel_m, grid.pixel_m);
  EXPECT_EQ(back.zone, 31);
  EXPECT_TRUE(back.northern);
  header.map_info.reset();
  EXPECT_THROW(orthoGridFromHeader(header), std::invalid_argument);
}

TEST(ExtrinsicRefinement, OptionsSayWhatIsWrong) {
  ExtrinsicRefinementOptions options;
  EXPECT_NO_THROW(options.validate());
  options.search_radius_m = 0.0;
  try {
    options.validate();
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "ExtrinsicRefinementOptions: search_radius_m must be > 0, got 0");
  }
  options = {};
  options.coarse_search_radius_m = -0.1;
  try {
    options.validate();
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "ExtrinsicRefinementOptions: coarse_search_radius_m must be > 0, got -0.1");
  }
  options.coarse_pixel_m = 0.0;  // no coarse step: its other fields are not used
  EXPECT_NO_THROW(options.validate());
}

}  // namespace
}  // namespace hsmap
