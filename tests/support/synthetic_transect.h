#pragma once
// A synthetic survey transect for the engine's recovery tests and benchmarks:
// a vehicle flying north 3 m above an undulating seabed (W = local NED),
// an RGB camera looking down, an INS on the body, a push-broom UHI camera.
//
// Truth. The vehicle's motion is analytic (smooth weaving, rolling, pitching,
// heading changes); the camera trajectory T_W_C(t) used as truth is the
// uniform cubic SE(3) B-spline whose control points are samples of that
// motion (control point j at t0 + (j - 1) dt, see se3_bspline.h), so spline
// problems have an exactly representable truth. Keyframe poses are the
// spline at the keyframe times.
//
// Frames: body B = x forward, y starboard, z down; camera C = x starboard,
// y aft, z down (T_B_C below, with a lever arm); UHI U = a line camera close
// to C (x along the line = starboard), rotated and offset by T_C_U.
//
// Measurements: pixels with Gaussian noise (and optional gross outliers drawn
// uniformly over the image), INS position of B and attitude of B with
// Gaussian noise, push-broom observations of known 3D points (fixed-point
// form): a random pixel u of a line, a point on its ray (with an across-line
// offset drawn from the across-line sigma) at a random range, then u with
// Gaussian noise.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3.h"
#include "core/geometry/se3_bspline.h"
#include "core/geometry/so3.h"
#include "core/graph/factor_graph.h"
#include "core/graph/values.h"
#include "factors/ins_attitude_factor.h"
#include "factors/ins_position_factor.h"
#include "factors/pushbroom_line_factor.h"
#include "factors/reprojection_factor.h"
#include "factors/spline_timing.h"

namespace hsmap::test {

struct TransectConfig {
  unsigned seed = 1;
  int num_keyframes = 20;
  double keyframe_interval_s = 1.0;
  double speed_m_s = 0.5;
  double altitude_m = 3.0;
  double seabed_depth_m = 20.0;
  // Scales the roll/pitch/heading oscillations of the vehicle (1 = a few degrees).
  double dynamics = 1.0;
  double spline_dt_s = 0.1;

  int num_landmarks = 500;
  double pixel_sigma = 0.5;
  double outlier_fraction = 0.0;
  double ins_sigma_horizontal_m = 0.05;
  double ins_sigma_depth_m = 0.02;
  double ins_sigma_roll_pitch_deg = 0.1;
  double ins_sigma_heading_deg = 0.5;

  // Start: truth perturbed by these sigmas.
  double start_pose_sigma_m = 0.2;
  double start_pose_sigma_deg = 2.0;
  double start_landmark_sigma_m = 0.2;
};

struct PixelObservation {
  int keyframe = 0;
  int landmark = 0;
  Eigen::Vector2d pixel;
  bool outlier = false;
};

struct Transect {
  TransectConfig config;
  PinholeRadtanParameters camera;
  SE3d T_B_C;
  SE3Splined truth_spline{0.0, 1.0, std::vector<SE3d>(4)};
  std::vector<double> keyframe_times;
  std::vector<SE3d> T_W_C;  // truth at the keyframes
  std::vector<Eigen::Vector3d> p_W;
  std::vector<PixelObservation> observations;
  std::vector<Eigen::Vector3d> ins_p_W_B;
  std::vector<Eigen::Quaterniond> ins_q_W_B;
  std::vector<SE3d> start_T_W_C;
  std::vector<Eigen::Vector3d> start_p_W;
};

inline double seabedDepth(const TransectConfig& config, double north, double east) {
  return config.seabed_depth_m + 0.3 * std::sin(0.5 * north) * std::cos(0.7 * east);
}

// T_W_B of the vehicle at time t.
inline SE3d vehicleMotion(const TransectConfig& config, double t) {
  const Eigen::Vector3d p(config.speed_m_s * t, 0.4 * std::sin(0.15 * t),
                          config.seabed_depth_m - config.altitude_m + 0.15 * std::sin(0.4 * t));
  const double a = config.dynamics;
  const double roll_deg = a * 3.0 * std::sin(0.9 * t + 0.3);
  const double pitch_deg = a * 2.5 * std::sin(0.7 * t);
  const double heading_deg = a * 3.0 * std::sin(0.1 * t) + 0.5 * a * std::sin(1.3 * t);
  return SE3d(quaternionFromRollPitchHeadingDeg(roll_deg, pitch_deg, heading_deg), p);
}

inline SE3d cameraOnBody() {
  Eigen::Matrix3d R_B_C;
  R_B_C.col(0) = Eigen::Vector3d(0, 1, 0);   // x_C = starboard
  R_B_C.col(1) = Eigen::Vector3d(-1, 0, 0);  // y_C = aft
  R_B_C.col(2) = Eigen::Vector3d(0, 0, 1);   // z_C = down
  return SE3d(Eigen::Quaterniond(R_B_C), Eigen::Vector3d(0.4, 0.0, 0.3));
}

inline PinholeRadtanParameters downLookingCamera() {
  PinholeRadtanParameters camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = 500.0;
  camera.fy = 500.0;
  camera.cx = 319.5;
  camera.cy = 239.5;
  camera.distortion = {-0.05, 0.01, 0.001, -0.001, 0.0};
  return camera;
}

// The spline T_W_C(t) covering [t_begin, t_end] with knot spacing dt, control
// points sampled from the vehicle motion (see the header comment).
inline SE3Splined truthSpline(const TransectConfig& config, const SE3d& T_B_C, double t_begin,
                              double t_end) {
  const double dt = config.spline_dt_s;
  const int num_control_points = static_cast<int>(std::ceil((t_end - t_begin) / dt - 1e-9)) + 3;
  std::vector<SE3d> control_points;
  for (int j = 0; j < num_control_points; ++j) {
    control_points.push_back(vehicleMotion(config, t_begin + (j - 1) * dt) * T_B_C);
  }
  return SE3Splined(t_begin, dt, std::move(control_points));
}

template <class Rng>
Vector6d gaussian6(Rng& rng, double sigma_translation, double sigma_rotation) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Vector6d xi;
  for (int i = 0; i < 3; ++i) xi[i] = sigma_translation * normal(rng);
  for (int i = 3; i < 6; ++i) xi[i] = sigma_rotation * normal(rng);
  return xi;
}

inline Transect makeTransect(const TransectConfig& config) {
  constexpr double kDeg = M_PI / 180.0;
  Transect transect;
  transect.config = config;
  transect.camera = downLookingCamera();
  transect.T_B_C = cameraOnBody();
  const PinholeRadtanCamera camera(transect.camera);
  std::mt19937 rng(config.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);

  const double duration = (config.num_keyframes - 1) * config.keyframe_interval_s;
  transect.truth_spline = truthSpline(config, transect.T_B_C, 0.0, duration);
  for (int k = 0; k < config.num_keyframes; ++k) {
    const double t = std::min(k * config.keyframe_interval_s, transect.truth_spline.validEnd());
    transect.keyframe_times.push_back(t);
    transect.T_W_C.push_back(transect.truth_spline.pose(t));
  }

  // Landmarks on the seabed under the track, each seen by at least
  // kMinViews keyframes (a landmark seen once has no depth), sorted north so
  // each keyframe only projects the ones near it.
  constexpr int kMinViews = 3;
  const double half_swath = 0.5 * transect.camera.width / transect.camera.fx * config.altitude_m;
  const double half_along = 0.5 * transect.camera.height / transect.camera.fy * config.altitude_m;
  const double north_begin = transect.T_W_C.front().t.x() - half_along;
  const double north_end = transect.T_W_C.back().t.x() + half_along;
  const double reach = 2.0 * half_along + 1.0;
  auto keyframesNear = [&](double north) {
    // Keyframes are evenly spaced in time and (nearly) in north.
    const double spacing = config.speed_m_s * config.keyframe_interval_s;
    const int first = std::max(0, static_cast<int>(std::floor((north - reach) / spacing)));
    const int last = std::min(config.num_keyframes - 1,
                              static_cast<int>(std::ceil((north + reach) / spacing)));
    return std::make_pair(first, last);
  };
  auto visible = [&](int k, const Eigen::Vector3d& p_W, Eigen::Vector2d* pixel) {
    const Eigen::Vector3d p_C = transect.T_W_C[k].inverse() * p_W;
    if (p_C.z() < 0.5) return false;
    *pixel = camera.project(p_C);
    return camera.isInImage(*pixel);
  };
  while (static_cast<int>(transect.p_W.size()) < config.num_landmarks) {
    const double north = north_begin + (north_end - north_begin) * uniform(rng);
    const double east = 2.0 * (uniform(rng) - 0.5) * half_swath;
    const Eigen::Vector3d p_W(north, east, seabedDepth(config, north, east));
    int views = 0;
    const auto [first, last] = keyframesNear(north);
    Eigen::Vector2d pixel;
    for (int k = first; k <= last; ++k) views += visible(k, p_W, &pixel) ? 1 : 0;
    if (views >= kMinViews) transect.p_W.push_back(p_W);
  }
  std::sort(transect.p_W.begin(), transect.p_W.end(),
            [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.x() < b.x(); });

  for (int k = 0; k < config.num_keyframes; ++k) {
    const double north = transect.T_W_C[k].t.x();
    auto begin = std::lower_bound(transect.p_W.begin(), transect.p_W.end(), north - reach,
                                  [](const Eigen::Vector3d& p, double x) { return p.x() < x; });
    for (auto it = begin; it != transect.p_W.end() && it->x() < north + reach; ++it) {
      Eigen::Vector2d pixel;
      if (!visible(k, *it, &pixel)) continue;
      PixelObservation observation;
      observation.keyframe = k;
      observation.landmark = static_cast<int>(it - transect.p_W.begin());
      observation.pixel =
          pixel + config.pixel_sigma * Eigen::Vector2d(normal(rng), normal(rng));
      if (uniform(rng) < config.outlier_fraction) {
        observation.outlier = true;
        observation.pixel = Eigen::Vector2d(uniform(rng) * (camera.width() - 1),
                                            uniform(rng) * (camera.height() - 1));
      }
      transect.observations.push_back(observation);
    }
  }

  const SE3d T_C_B = transect.T_B_C.inverse();
  for (int k = 0; k < config.num_keyframes; ++k) {
    const SE3d T_W_B = transect.T_W_C[k] * T_C_B;
    transect.ins_p_W_B.push_back(
        T_W_B.t + Eigen::Vector3d(config.ins_sigma_horizontal_m * normal(rng),
                                  config.ins_sigma_horizontal_m * normal(rng),
                                  config.ins_sigma_depth_m * normal(rng)));
    const Eigen::Vector3d attitude_noise(config.ins_sigma_roll_pitch_deg * kDeg * normal(rng),
                                         config.ins_sigma_roll_pitch_deg * kDeg * normal(rng),
                                         config.ins_sigma_heading_deg * kDeg * normal(rng));
    transect.ins_q_W_B.push_back(T_W_B.q * expSO3(attitude_noise));
    transect.start_T_W_C.push_back(
        transect.T_W_C[k] *
        SE3d::exp(gaussian6(rng, config.start_pose_sigma_m, config.start_pose_sigma_deg * kDeg)));
  }
  for (const Eigen::Vector3d& p : transect.p_W) {
    transect.start_p_W.push_back(
        p + config.start_landmark_sigma_m * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)));
  }
  return transect;
}

inline NoiseModel insPositionNoise(const TransectConfig& config) {
  return NoiseModel::fromSigmas(Eigen::Vector3d(
      config.ins_sigma_horizontal_m, config.ins_sigma_horizontal_m, config.ins_sigma_depth_m));
}

inline NoiseModel insAttitudeNoise(const TransectConfig& config) {
  constexpr double kDeg = M_PI / 180.0;
  return NoiseModel::fromSigmas(Eigen::Vector3d(config.ins_sigma_roll_pitch_deg * kDeg,
                                                config.ins_sigma_roll_pitch_deg * kDeg,
                                                config.ins_sigma_heading_deg * kDeg));
}

// Keyframe bundle adjustment: X(k), L(i), one ReprojectionFactor per pixel,
// INS position and attitude on every keyframe. Values start at the noisy start.
inline void buildBundleAdjustment(const Transect& transect, RobustLoss loss, FactorGraph* graph,
                                  Values* values) {
  const NoiseModel pixel_noise = NoiseModel::isotropic(2, transect.config.pixel_sigma);
  for (const PixelObservation& observation : transect.observations) {
    graph->emplace<ReprojectionFactor>(X(observation.keyframe), L(observation.landmark),
                                       observation.pixel, transect.camera, pixel_noise, loss);
  }
  for (std::size_t k = 0; k < transect.T_W_C.size(); ++k) {
    graph->emplace<InsPositionFactor>(X(k), transect.ins_p_W_B[k], transect.T_B_C,
                                      insPositionNoise(transect.config));
    graph->emplace<InsAttitudeFactor>(X(k), transect.ins_q_W_B[k], transect.T_B_C,
                                      insAttitudeNoise(transect.config));
    values->insertPose(X(k), transect.start_T_W_C[k].q, transect.start_T_W_C[k].t);
  }
  for (std::size_t i = 0; i < transect.p_W.size(); ++i) {
    values->insertPoint(L(i), transect.start_p_W[i]);
  }
}

// Push-broom observations of known points (fixed-point form) for scan lines
// recorded at `line_times` (recorded clock), with the true extrinsic T_C_U
// and time offset d (true time = recorded + d).
struct PushbroomPointObservation {
  PushbroomObservation observation;
  Eigen::Vector3d p_W;
};

inline PushbroomParameters uhiCamera() {
  PushbroomParameters camera;
  camera.samples = 960;
  camera.f = 1000.0;
  camera.cx = 479.5;
  camera.distortion = {-0.03, 0.005};
  return camera;
}

// Across-line sigma: half a pixel's angle.
inline double acrossLineSigma(const PushbroomParameters& camera) { return 0.5 / camera.f; }

template <class Rng>
std::vector<PushbroomPointObservation> makePushbroomObservations(
    const SE3Splined& spline, const SE3d& T_C_U, double d, const PushbroomParameters& parameters,
    const std::vector<double>& line_times, int points_per_line, double u_sigma, double altitude_m,
    Rng& rng) {
  const PushbroomCamera camera(parameters);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<PushbroomPointObservation> observations;
  for (const double t_recorded : line_times) {
    const SE3d T_W_U = spline.pose(t_recorded + d) * T_C_U;
    for (int k = 0; k < points_per_line; ++k) {
      const double u = uniform(rng) * (parameters.samples - 1);
      const std::optional<Eigen::Vector3d> ray = camera.unproject(u);
      if (!ray) continue;
      Eigen::Vector3d p_U = *ray / ray->z();  // (x, 0, 1)
      p_U.y() = acrossLineSigma(parameters) * normal(rng);
      p_U *= altitude_m * (0.8 + 0.4 * uniform(rng));
      PushbroomPointObservation observation;
      observation.observation.t_recorded = t_recorded;
      observation.observation.u = u + u_sigma * normal(rng);
      observation.p_W = T_W_U * p_U;
      observations.push_back(observation);
    }
  }
  return observations;
}

// The UHI's true mounting: close to the camera, slightly rotated.
inline SE3d uhiOnCamera() {
  constexpr double kDeg = M_PI / 180.0;
  return SE3d(expSO3(Eigen::Vector3d(1.0 * kDeg, -0.5 * kDeg, 0.3 * kDeg)),
              Eigen::Vector3d(0.1, 0.05, 0.02));
}

}  // namespace hsmap::test
