#include "pipelines/simulate/motion/ins_synthesis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/geometry/so3.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

constexpr double kRadToDeg = 57.295779513082320877;

const LocalNedFrame& frame() {
  static const LocalNedFrame w_frame(GeodeticPoint{43.0, 5.0, 0.0});
  return w_frame;
}

// A lawnmower (headings near 0 and 180 degrees, through the wrap) over a flat seabed.
const VehicleTrajectory& trajectory() {
  static const VehicleTrajectory instance = [] {
    VehicleMotionConfig config;
    config.pattern = MotionPattern::lawnmower;
    config.length_m = 10.0;
    config.lanes = 2;
    config.start_north_m = -5.0;
    config.start_time_s = 1000.0;
    config.seed = 3;
    return VehicleTrajectory(config, [](double, double) { return 12.0; });
  }();
  return instance;
}

InsNoiseConfig noNoise() {
  InsNoiseConfig noise;
  noise.horizontal_noise_m = 0.0;
  noise.horizontal_drift_m_per_sqrt_s = 0.0;
  noise.depth_noise_m = 0.0;
  noise.depth_drift_m_per_sqrt_s = 0.0;
  noise.roll_pitch_noise_deg = 0.0;
  noise.heading_noise_deg = 0.0;
  return noise;
}

double standardDeviation(const std::vector<double>& values) {
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= values.size();
  double sum = 0.0;
  for (double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / (values.size() - 1));
}

// Signed difference a - b of two angles in degrees, in [-180, 180].
double angleDifferenceDeg(double a, double b) { return std::remainder(a - b, 360.0); }

TEST(InsSynthesisTest, FixesAtTheRateFromTheBeginTime) {
  InsNoiseConfig noise = noNoise();
  noise.rate_hz = 4.0;
  const double t_begin = trajectory().startTime() + 0.3;
  const double t_end = trajectory().startTime() + 10.3;  // k = 40 lands exactly on it
  const InsTable table = synthesizeIns(trajectory(), noise, frame(), t_begin, t_end);
  EXPECT_TRUE(table.has_attitude);
  ASSERT_EQ(table.fixes.size(), 41u);
  for (std::size_t k = 0; k < table.fixes.size(); ++k) {
    EXPECT_EQ(table.fixes[k].t, t_begin + k / 4.0);
  }
  // The whole trajectory at 1 Hz: floor(duration) + 1 fixes, the last within it.
  const InsTable whole = synthesizeIns(trajectory(), noNoise(), frame(), trajectory().startTime(),
                                       trajectory().endTime());
  const double duration = trajectory().endTime() - trajectory().startTime();
  EXPECT_EQ(whole.fixes.size(), static_cast<std::size_t>(std::floor(duration)) + 1);
  EXPECT_LE(whole.fixes.back().t, trajectory().endTime());
}

TEST(InsSynthesisTest, WithoutNoiseFixesConvertBackToTheTruePose) {
  const InsTable table = synthesizeIns(trajectory(), noNoise(), frame(), trajectory().startTime(),
                                       trajectory().endTime());
  bool saw_south = false;
  for (const InsFix& fix : table.fixes) {
    const SE3d T_W_B = trajectory().T_W_B(fix.t);
    const Eigen::Vector3d p_W = frame().toNed({fix.lat_deg, fix.lon_deg, fix.depth_m});
    EXPECT_LT((p_W - T_W_B.t).norm(), 1e-6) << "t = " << fix.t;
    const Eigen::Quaterniond q =
        quaternionFromRollPitchHeadingDeg(fix.roll_deg, fix.pitch_deg, fix.heading_deg);
    EXPECT_LT(logSO3(q.conjugate() * T_W_B.q).norm() * kRadToDeg, 1e-6) << "t = " << fix.t;
    EXPECT_GE(fix.heading_deg, 0.0);
    EXPECT_LT(fix.heading_deg, 360.0);
    saw_south = saw_south || std::abs(fix.heading_deg - 180.0) < 10.0;
  }
  EXPECT_TRUE(saw_south);
}

TEST(InsSynthesisTest, WhiteNoiseMatchesTheConfiguredSigmas) {
  InsNoiseConfig noise;  // default sigmas
  noise.horizontal_drift_m_per_sqrt_s = 0.0;
  noise.depth_drift_m_per_sqrt_s = 0.0;
  noise.rate_hz = 25.0;
  const InsTable table = synthesizeIns(trajectory(), noise, frame(), trajectory().startTime(),
                                       trajectory().endTime());
  ASSERT_GT(table.fixes.size(), 1500u);  // enough for a 2 % standard-deviation estimate
  std::vector<double> north, east, down, roll, pitch, heading;
  for (const InsFix& fix : table.fixes) {
    const SE3d T_W_B = trajectory().T_W_B(fix.t);
    const Eigen::Vector3d error = frame().toNed({fix.lat_deg, fix.lon_deg, fix.depth_m}) - T_W_B.t;
    north.push_back(error.x());
    east.push_back(error.y());
    down.push_back(error.z());
    const Eigen::Vector3d truth = rollPitchHeadingDegFromQuaternion(T_W_B.q);
    roll.push_back(angleDifferenceDeg(fix.roll_deg, truth[0]));
    pitch.push_back(fix.pitch_deg - truth[1]);
    heading.push_back(angleDifferenceDeg(fix.heading_deg, truth[2]));
  }
  EXPECT_NEAR(standardDeviation(north), noise.horizontal_noise_m, 0.2 * noise.horizontal_noise_m);
  EXPECT_NEAR(standardDeviation(east), noise.horizontal_noise_m, 0.2 * noise.horizontal_noise_m);
  EXPECT_NEAR(standardDeviation(down), noise.depth_noise_m, 0.2 * noise.depth_noise_m);
  EXPECT_NEAR(standardDeviation(roll), noise.roll_pitch_noise_deg, 0.2 * noise.roll_pitch_noise_deg);
  EXPECT_NEAR(standardDeviation(pitch), noise.roll_pitch_noise_deg,
              0.2 * noise.roll_pitch_noise_deg);
  EXPECT_NEAR(standardDeviation(heading), noise.heading_noise_deg, 0.2 * noise.heading_noise_deg);
}

TEST(InsSynthesisTest, DriftGrowsLikeTheSquareRootOfTime) {
  InsNoiseConfig noise = noNoise();
  noise.horizontal_drift_m_per_sqrt_s = 0.02;
  noise.depth_drift_m_per_sqrt_s = 0.002;
  // Across 300 seeds, the error 9 s and 36 s after the first fix.
  const double t_begin = trajectory().startTime();
  std::vector<double> horizontal_9, horizontal_36, depth_9, depth_36;
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    noise.seed = seed;
    const InsTable table = synthesizeIns(trajectory(), noise, frame(), t_begin, t_begin + 36.0);
    for (std::size_t k : {9u, 36u}) {
      const InsFix& fix = table.fixes.at(k);
      const Eigen::Vector3d error =
          frame().toNed({fix.lat_deg, fix.lon_deg, fix.depth_m}) - trajectory().T_W_B(fix.t).t;
      auto& horizontal = k == 9 ? horizontal_9 : horizontal_36;
      horizontal.push_back(error.x());
      horizontal.push_back(error.y());
      (k == 9 ? depth_9 : depth_36).push_back(error.z());
    }
    EXPECT_LT((frame().toNed({table.fixes[0].lat_deg, table.fixes[0].lon_deg,
                              table.fixes[0].depth_m}) -
               trajectory().T_W_B(t_begin).t)
                  .norm(),
              1e-6);  // no drift yet at the first fix
  }
  EXPECT_NEAR(standardDeviation(horizontal_9), 0.02 * 3.0, 0.2 * 0.02 * 3.0);
  EXPECT_NEAR(standardDeviation(horizontal_36), 0.02 * 6.0, 0.2 * 0.02 * 6.0);
  EXPECT_NEAR(standardDeviation(depth_9), 0.002 * 3.0, 0.2 * 0.002 * 3.0);
  EXPECT_NEAR(standardDeviation(depth_36), 0.002 * 6.0, 0.2 * 0.002 * 6.0);
  // sqrt(36 / 9) = 2.
  EXPECT_NEAR(standardDeviation(horizontal_36) / standardDeviation(horizontal_9), 2.0, 0.2 * 2.0);
}

TEST(InsSynthesisTest, SameSeedSameTableOtherSeedOtherTable) {
  InsNoiseConfig noise;
  const auto make = [&] {
    return synthesizeIns(trajectory(), noise, frame(), trajectory().startTime(),
                         trajectory().endTime());
  };
  const InsTable a = make(), b = make();
  noise.seed = 2;
  const InsTable c = make();
  ASSERT_EQ(a.fixes.size(), b.fixes.size());
  for (std::size_t k = 0; k < a.fixes.size(); ++k) {
    EXPECT_EQ(a.fixes[k].lat_deg, b.fixes[k].lat_deg);
    EXPECT_EQ(a.fixes[k].lon_deg, b.fixes[k].lon_deg);
    EXPECT_EQ(a.fixes[k].depth_m, b.fixes[k].depth_m);
    EXPECT_EQ(a.fixes[k].roll_deg, b.fixes[k].roll_deg);
    EXPECT_EQ(a.fixes[k].pitch_deg, b.fixes[k].pitch_deg);
    EXPECT_EQ(a.fixes[k].heading_deg, b.fixes[k].heading_deg);
  }
  EXPECT_NE(a.fixes[5].lat_deg, c.fixes[5].lat_deg);
}

TEST(InsSynthesisTest, TableWritesAndReadsBackAsInsCsv) {
  // Headings wrapped into [0, 360) and roll into (-180, 180] pass the reader's range checks.
  const InsTable table = synthesizeIns(trajectory(), InsNoiseConfig{}, frame(),
                                       trajectory().startTime(), trajectory().endTime());
  testing::TempFolder folder;
  writeInsCsv(folder / "ins.csv", table);
  const InsTable read = readInsCsv(folder / "ins.csv");
  ASSERT_EQ(read.fixes.size(), table.fixes.size());
  EXPECT_TRUE(read.has_attitude);
  EXPECT_EQ(read.fixes.back().heading_deg, table.fixes.back().heading_deg);
}

TEST(InsSynthesisTest, RejectsBadArguments) {
  try {
    synthesizeIns(trajectory(), noNoise(), frame(), trajectory().startTime(),
                  trajectory().endTime() + 1.0);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind(
                  "synthesizeIns: expected startTime() <= t_begin <= t_end <= endTime() = 1000 <= "
                  "1000 <= ",
                  0),
              0u)
        << e.what();
  }
  EXPECT_THROW(synthesizeIns(trajectory(), noNoise(), frame(), trajectory().startTime() + 2.0,
                             trajectory().startTime() + 1.0),
               std::invalid_argument);
  InsNoiseConfig noise;
  noise.heading_noise_deg = -0.1;
  try {
    noise.validate();
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "InsNoiseConfig: heading_noise_deg must be a finite number >= 0, got -0.1");
  }
  noise = {};
  noise.rate_hz = 0.0;
  EXPECT_THROW(noise.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
