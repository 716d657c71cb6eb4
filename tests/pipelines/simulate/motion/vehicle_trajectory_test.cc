#include "pipelines/simulate/motion/vehicle_trajectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/geometry/so3.h"

namespace hsmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

double flatSeabed(double, double) { return 10.0; }

// Gentle relief: within any 2 m x 2 m window z varies by less than 0.2 m.
double gentleSeabed(double north, double east) {
  return 10.0 + 0.05 * std::sin(north / 0.7) * std::cos(east / 0.9) + 0.05 * std::sin(north / 2.3);
}

// Gentle relief plus three rounded boulders 1.8 m tall (Gaussian, sigma
// 0.4 m), on and beside the transect. A vehicle blind to them would pass
// 0.2 m above their tops at 2 m altitude.
double boulderSeabed(double north, double east) {
  const double boulders[][2] = {{5.0, 0.3}, {11.0, -0.6}, {15.0, 0.0}};
  double z = gentleSeabed(north, east);
  for (const auto& b : boulders) {
    const double d2 = (north - b[0]) * (north - b[0]) + (east - b[1]) * (east - b[1]);
    z -= 1.8 * std::exp(-d2 / (2 * 0.4 * 0.4));
  }
  return z;
}

VehicleMotionConfig transectConfig() {
  VehicleMotionConfig config;  // 20 m at 0.3 m/s, 2 m altitude, 3 deg
  config.start_north_m = 0.0;
  config.start_time_s = 100.0;
  config.seed = 7;
  return config;
}

VehicleMotionConfig lawnmowerConfig() {
  VehicleMotionConfig config = transectConfig();
  config.pattern = MotionPattern::lawnmower;
  config.length_m = 8.0;
  config.lanes = 3;
  config.lane_spacing_m = 2.0;
  return config;
}

std::vector<double> sampleTimes(const VehicleTrajectory& trajectory, double dt) {
  std::vector<double> times;
  for (long long k = 0;; ++k) {
    const double t = trajectory.startTime() + k * dt;
    if (t > trajectory.endTime()) break;
    times.push_back(t);
  }
  return times;
}

// Independent reference of the smoothed envelope: highest seabed point (min
// z) within a 2 m x 2 m window sampled every 5 cm along x 10 cm across, then
// a Hann-weighted mean over +-1 m of arc length.
std::vector<double> referenceEnvelope(const LanePath& path, double (*seabed)(double, double),
                                      const std::vector<double>& s_grid) {
  std::vector<double> highest(s_grid.size());
  for (std::size_t i = 0; i < s_grid.size(); ++i) {
    double z = 1e9;
    for (double along = s_grid[i] - 1.0; along <= s_grid[i] + 1.0 + 1e-9; along += 0.05) {
      if (along < 0.0 || along > path.length()) continue;
      const PathPoint p = path.at(along);
      for (double across = -1.0; across <= 1.0 + 1e-9; across += 0.1) {
        z = std::min(z, seabed(p.north_m - across * std::sin(p.heading_rad),
                               p.east_m + across * std::cos(p.heading_rad)));
      }
    }
    highest[i] = z;
  }
  std::vector<double> smoothed(s_grid.size());
  for (std::size_t i = 0; i < s_grid.size(); ++i) {
    double sum = 0.0, total = 0.0;
    for (std::size_t j = 0; j < s_grid.size(); ++j) {
      const double d = std::abs(s_grid[j] - s_grid[i]);
      if (d >= 1.0) continue;
      const double w = 0.5 * (1.0 + std::cos(kPi * d));
      sum += w * highest[j];
      total += w;
    }
    smoothed[i] = sum / total;
  }
  return smoothed;
}

TEST(VehicleTrajectoryTest, SameSeedSamePosesBitForBitOtherSeedOtherPoses) {
  const VehicleTrajectory a(lawnmowerConfig(), gentleSeabed);
  const VehicleTrajectory b(lawnmowerConfig(), gentleSeabed);
  VehicleMotionConfig other = lawnmowerConfig();
  other.seed = 8;
  const VehicleTrajectory c(other, gentleSeabed);
  ASSERT_EQ(a.endTime(), b.endTime());
  for (double t : sampleTimes(a, 0.77)) {
    const SE3d pa = a.T_W_B(t), pb = b.T_W_B(t);
    EXPECT_EQ(pa.t, pb.t);
    EXPECT_EQ(pa.q.coeffs(), pb.q.coeffs());
  }
  const double t = a.startTime() + 10.0;
  EXPECT_NE(a.T_W_B(t).q.coeffs(), c.T_W_B(t).q.coeffs());
}

TEST(VehicleTrajectoryTest, StartsAtTheStartPointAndEndsAtThePathEnd) {
  const VehicleTrajectory trajectory(transectConfig(), flatSeabed);
  EXPECT_EQ(trajectory.startTime(), 100.0);
  // Mean speed 0.3 m/s with +-20 %: 20 m take between 20/0.36 and 20/0.24 s.
  const double duration = trajectory.endTime() - trajectory.startTime();
  EXPECT_GT(duration, 20.0 / 0.36);
  EXPECT_LT(duration, 20.0 / 0.24);
  EXPECT_NEAR(trajectory.arcLength(trajectory.endTime()), 20.0, 1e-9);
  const SE3d start = trajectory.T_W_B(trajectory.startTime());
  const SE3d end = trajectory.T_W_B(trajectory.endTime());
  EXPECT_NEAR((start.t - Eigen::Vector3d(0.0, 0.0, 8.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((end.t - Eigen::Vector3d(20.0, 0.0, 8.0)).norm(), 0.0, 1e-9);
}

TEST(VehicleTrajectoryTest, KeepsAltitudeOverGentleReliefAndClearsBoulders) {
  const VehicleMotionConfig config = transectConfig();
  for (auto seabed : {&gentleSeabed, &boulderSeabed}) {
    const VehicleTrajectory trajectory(config, seabed);
    std::vector<double> times = sampleTimes(trajectory, 0.1);
    std::vector<double> s_grid;
    for (double t : times) s_grid.push_back(trajectory.arcLength(t));
    const std::vector<double> reference = referenceEnvelope(trajectory.path(), seabed, s_grid);
    double lowest_clearance = 1e9;
    for (std::size_t i = 0; i < times.size(); ++i) {
      const Eigen::Vector3d p = trajectory.T_W_B(times[i]).t;
      EXPECT_NEAR(reference[i] - p.z(), config.altitude_m, 0.3) << "t = " << times[i];
      lowest_clearance = std::min(lowest_clearance, seabed(p.x(), p.y()) - p.z());
    }
    EXPECT_GE(lowest_clearance, 0.5);
    // The envelope is never below the seabed under the path: full altitude.
    EXPECT_GE(lowest_clearance, config.altitude_m - 1e-3);
    if (seabed == &gentleSeabed) {
      EXPECT_LE(lowest_clearance, config.altitude_m + 0.2);
    }
  }
}

TEST(VehicleTrajectoryTest, SpeedOverGroundStaysInItsRangeAndVaries) {
  for (const VehicleMotionConfig& config : {transectConfig(), lawnmowerConfig()}) {
    const VehicleTrajectory trajectory(config, gentleSeabed);
    const double dt = 0.01;
    const std::vector<double> times = sampleTimes(trajectory, dt);
    double slowest = 1e9, fastest = 0.0;
    for (std::size_t i = 1; i < times.size(); ++i) {
      const Eigen::Vector3d a = trajectory.T_W_B(times[i - 1]).t, b = trajectory.T_W_B(times[i]).t;
      const double speed = std::hypot(b.x() - a.x(), b.y() - a.y()) / (times[i] - times[i - 1]);
      slowest = std::min(slowest, speed);
      fastest = std::max(fastest, speed);
    }
    const double v0 = config.speed_m_s, a = config.speed_variation;
    EXPECT_GE(slowest, v0 * (1 - a) - 1e-6);
    EXPECT_LE(fastest, v0 * (1 + a) + 1e-6);
    // The trajectory is longer than the slowest speed period (50 s), so the
    // dominant term (weight 0.7 of 1) peaks and dips at least once.
    EXPECT_GE(fastest - slowest, 0.75 * a * v0);
  }
}

TEST(VehicleTrajectoryTest, RollPitchAndHeadingWanderStayWithinTheirAmplitudes) {
  VehicleMotionConfig config = transectConfig();
  config.roll_pitch_amplitude_deg = 4.0;
  config.heading_wander_deg = 5.0;
  const VehicleTrajectory trajectory(config, flatSeabed);
  double max_roll = 0.0, max_pitch = 0.0, max_heading = 0.0;
  for (double t : sampleTimes(trajectory, 0.05)) {
    const Eigen::Vector3d rph = rollPitchHeadingDegFromQuaternion(trajectory.T_W_B(t).q);
    max_roll = std::max(max_roll, std::abs(rph[0]));
    max_pitch = std::max(max_pitch, std::abs(rph[1]));
    max_heading = std::max(max_heading, std::abs(rph[2]));  // the path heads north: 0
  }
  EXPECT_LE(max_roll, 4.0 + 1e-9);
  EXPECT_LE(max_pitch, 4.0 + 1e-9);
  EXPECT_LE(max_heading, 5.0 + 1e-9);
  // Each is seen at >= 0.4 of its amplitude (the dominant sinusoid peaks).
  EXPECT_GE(max_roll, 0.4 * 4.0);
  EXPECT_GE(max_pitch, 0.4 * 4.0);
  EXPECT_GE(max_heading, 0.4 * 5.0);
}

// Largest finite-difference acceleration and largest change of it between
// neighbouring samples, for positions and body angular velocity.
struct FiniteDifferenceExtremes {
  double max_acceleration = 0.0;
  double max_acceleration_step = 0.0;
  double max_angular_acceleration = 0.0;
  double max_angular_acceleration_step = 0.0;
};

FiniteDifferenceExtremes finiteDifferences(const VehicleTrajectory& trajectory, double dt) {
  const std::vector<double> times = sampleTimes(trajectory, dt);
  std::vector<SE3d> poses;
  for (double t : times) poses.push_back(trajectory.T_W_B(t));
  std::vector<Eigen::Vector3d> velocity, angular_velocity;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    velocity.push_back((poses[i].t - poses[i - 1].t) / dt);
    angular_velocity.push_back(logSO3(poses[i - 1].q.conjugate() * poses[i].q) / dt);
  }
  FiniteDifferenceExtremes extremes;
  Eigen::Vector3d previous_a = Eigen::Vector3d::Zero(), previous_alpha = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i < velocity.size(); ++i) {
    const Eigen::Vector3d a = (velocity[i] - velocity[i - 1]) / dt;
    const Eigen::Vector3d alpha = (angular_velocity[i] - angular_velocity[i - 1]) / dt;
    extremes.max_acceleration = std::max(extremes.max_acceleration, a.norm());
    extremes.max_angular_acceleration = std::max(extremes.max_angular_acceleration, alpha.norm());
    if (i > 1) {
      extremes.max_acceleration_step =
          std::max(extremes.max_acceleration_step, (a - previous_a).norm());
      extremes.max_angular_acceleration_step =
          std::max(extremes.max_angular_acceleration_step, (alpha - previous_alpha).norm());
    }
    previous_a = a;
    previous_alpha = alpha;
  }
  return extremes;
}

TEST(VehicleTrajectoryTest, IsSmoothAccelerationsAreContinuousAndBounded) {
  // Over boulders and through lawnmower turns. A jump in acceleration would
  // show as a step between neighbouring samples that does not shrink with
  // dt; for a C2 trajectory the largest step halves when dt halves.
  VehicleMotionConfig config = lawnmowerConfig();
  for (const VehicleMotionConfig& c : {transectConfig(), config}) {
    const VehicleTrajectory trajectory(c, boulderSeabed);
    const FiniteDifferenceExtremes coarse = finiteDifferences(trajectory, 0.02);
    const FiniteDifferenceExtremes fine = finiteDifferences(trajectory, 0.01);
    // Bounded: a slow survey vehicle, well under 0.5 m/s^2 and 10 deg/s^2.
    EXPECT_LT(fine.max_acceleration, 0.5);
    EXPECT_LT(fine.max_angular_acceleration, 10.0 * kPi / 180.0);
    // Continuous.
    EXPECT_LT(fine.max_acceleration_step, 0.7 * coarse.max_acceleration_step);
    EXPECT_LT(fine.max_angular_acceleration_step, 0.7 * coarse.max_angular_acceleration_step);
    EXPECT_LT(fine.max_acceleration_step, 0.01);
  }
}

TEST(VehicleTrajectoryTest, LawnmowerVisitsEveryLaneInAlternatingDirections) {
  const VehicleMotionConfig config = lawnmowerConfig();
  const VehicleTrajectory trajectory(config, flatSeabed);
  for (int lane = 0; lane < config.lanes; ++lane) {
    const double east = config.start_east_m + lane * config.lane_spacing_m;
    double south_most = 1e9, north_most = -1e9;
    int samples = 0;
    for (double t : sampleTimes(trajectory, 0.1)) {
      const SE3d pose = trajectory.T_W_B(t);
      if (std::abs(pose.t.y() - east) > 1e-9) continue;
      ++samples;
      south_most = std::min(south_most, pose.t.x());
      north_most = std::max(north_most, pose.t.x());
      const double heading = rollPitchHeadingDegFromQuaternion(pose.q)[2];
      const double lane_heading = lane % 2 == 0 ? 0.0 : 180.0;
      const double off = std::remainder(heading - lane_heading, 360.0);
      EXPECT_LE(std::abs(off), config.heading_wander_deg + 1e-9) << "lane " << lane;
    }
    EXPECT_GT(samples, 0) << "lane " << lane;
    EXPECT_LT(south_most, config.start_north_m + 0.2) << "lane " << lane;
    EXPECT_GT(north_most, config.start_north_m + config.length_m - 0.2) << "lane " << lane;
  }
}

TEST(VehicleTrajectoryTest, TimesOutsideTheTrajectoryThrow) {
  const VehicleTrajectory trajectory(transectConfig(), flatSeabed);
  EXPECT_NO_THROW(trajectory.T_W_B(trajectory.endTime()));
  try {
    trajectory.T_W_B(99.5);
    FAIL() << "no exception";
  } catch (const std::out_of_range& e) {
    EXPECT_EQ(std::string(e.what()).rfind("VehicleTrajectory::T_W_B: time 99.5 s is outside the "
                                          "trajectory [100, ", 0),
              0u)
        << e.what();
  }
  EXPECT_THROW(trajectory.T_W_B(trajectory.endTime() + 1e-9), std::out_of_range);
  EXPECT_THROW(trajectory.arcLength(NAN), std::out_of_range);
}

TEST(VehicleTrajectoryTest, ConfigValidationNamesTheField) {
  const auto message = [](const VehicleMotionConfig& config) {
    try {
      config.validate();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  VehicleMotionConfig config;
  EXPECT_EQ(message(config), "no exception");
  config.speed_variation = 0.95;
  EXPECT_EQ(message(config), "VehicleMotionConfig: speed_variation must be in [0, 0.9], got 0.95");
  config = {};
  config.altitude_m = 0.0;
  EXPECT_EQ(message(config), "VehicleMotionConfig: altitude_m must be a finite number > 0, got 0");
  config = {};
  config.lanes = 3;
  EXPECT_EQ(message(config),
            "VehicleMotionConfig: a transect has lanes = 1, got 3 (use the lawnmower pattern for "
            "several lanes)");
  config.pattern = MotionPattern::lawnmower;
  config.lanes = 1;
  EXPECT_EQ(message(config), "VehicleMotionConfig: a lawnmower needs lanes >= 2, got 1");
  config = {};
  config.start_time_s = NAN;
  EXPECT_EQ(message(config), "VehicleMotionConfig: start_time_s must be finite, got nan");
  // The constructor validates too.
  EXPECT_THROW(VehicleTrajectory(config, flatSeabed), std::invalid_argument);

  EXPECT_EQ(parseMotionPattern(motionPatternName(MotionPattern::lawnmower)),
            MotionPattern::lawnmower);
  EXPECT_EQ(parseMotionPattern("transect"), MotionPattern::transect);
  EXPECT_THROW(parseMotionPattern("spiral"), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
