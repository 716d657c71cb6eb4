#include "pipelines/joint/joint_problem.h"

#include "core/util/thread_budget.h"

#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <tuple>
#include <string>
#include <unordered_map>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/graph/factor_graph.h"
#include "core/graph/key.h"
#include "core/graph/values.h"
#include "factors/extrinsic_prior_factor.h"
#include "factors/pushbroom_camera_point_factor.h"
#include "factors/pushbroom_intrinsics_prior_factor.h"
#include "factors/pushbroom_line_factor.h"
#include "factors/spline_ins_attitude_factor.h"
#include "factors/spline_ins_position_factor.h"
#include "factors/spline_reprojection_factor.h"
#include "factors/spline_smoothness_factor.h"
#include "factors/spline_timing.h"
#include "factors/time_offset_prior_factor.h"
#include "solvers/graph_problem.h"
#include "solvers/marginal_covariance.h"
#include "solvers/robust_outliers.h"

namespace hsmap {

void JointOptions::validate() const {
  auto positive = [](const char* name, double value) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw std::invalid_argument(std::string("JointOptions::") + name + ": expected a finite value > 0, got " +
                                  std::to_string(value));
    }
  };
  positive("pixel_sigma_px", pixel_sigma_px);
  positive("other_frame_sigma_factor", other_frame_sigma_factor);
  positive("huber_sigmas", huber_sigmas);
  positive("start_gate_px", start_gate_px);
  positive("sigma_match_m", sigma_match_m);
  if (sigma_match_along_m < 0.0 || !std::isfinite(sigma_match_along_m)) {
    throw std::invalid_argument("JointOptions::sigma_match_along_m: expected >= 0 (0: sigma_match_m), got " +
                                std::to_string(sigma_match_along_m));
  }
  positive("tie_robust_scale", tie_robust_scale);
  if (!(min_frame_weight_in_support >= 0.0) || !std::isfinite(min_frame_weight_in_support)) {
    throw std::invalid_argument("JointOptions::min_frame_weight_in_support: expected >= 0 (0: no weight asked), got " +
                                std::to_string(min_frame_weight_in_support));
  }
  positive("sigma_linear_acceleration", sigma_linear_acceleration);
  positive("sigma_angular_acceleration", sigma_angular_acceleration);
  positive("weak_fraction_of_prior", weak_fraction_of_prior);
  positive("inseparable_correlation", inseparable_correlation);
  for (const auto& [name, value, least] :
       {std::tuple{"min_tie_points", min_tie_points, 1}, std::tuple{"min_frames_in_support", min_frames_in_support, 1},
        std::tuple{"max_iterations", max_iterations, 1}, std::tuple{"num_threads", num_threads, 0},
        std::tuple{"max_rewindows", max_rewindows, 0}}) {
    if (value < least) {
      throw std::invalid_argument(std::string("JointOptions::") + name + ": expected >= " + std::to_string(least) +
                                  ", got " + std::to_string(value));
    }
  }
}

bool JointInputs::estimatesUhiIntrinsics() const {
  for (double sigma : uhi_intrinsics_sigma) {
    if (sigma > 0.0) return true;
  }
  return false;
}

namespace {

constexpr double kDefaultRangeM = 2.0;
constexpr const char* kIntrinsicNames[PushbroomCamera::kNumIntrinsics] = {"f", "cx", "distortion[0]",
                                                                          "distortion[1]"};
// The components of T_C_U's tangent [rho; phi] and of d, as the warnings name them.
constexpr const char* kExtrinsicComponentNames[7] = {
    "T_C_U's translation along U's x",
    "T_C_U's translation along U's y",
    "T_C_U's translation along U's z",
    "T_C_U's rotation about U's x (the line's axis)",
    "T_C_U's rotation about U's y (the line's normal)",
    "T_C_U's rotation about U's z (the optical axis)",
    "the time offset d"};

PushbroomParameters withIntrinsics(PushbroomParameters camera,
                                   const std::array<double, PushbroomCamera::kNumIntrinsics>& k) {
  camera.f = k[0];
  camera.cx = k[1];
  camera.distortion = {k[2], k[3]};
  return camera;
}
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

void checkInputs(const JointInputs& in) {
  if (in.map_W == nullptr || in.frontend == nullptr || in.frame_times == nullptr || in.ins == nullptr) {
    throw std::invalid_argument(
        "solveJointProblem: the map, the front-end result, the frame times and the INS track are "
        "required");
  }
  if (in.estimatesUhiIntrinsics() && in.surface_trajectory == nullptr) {
    throw std::invalid_argument(
        "solveJointProblem: the UHI intrinsics are estimated only with tie points carried by the "
        "trajectory (JointInputs::surface_trajectory)");
  }
  if (in.spline.numControlPoints() < 5) {
    throw std::invalid_argument("solveJointProblem: the spline needs at least 5 control points, got " +
                                std::to_string(in.spline.numControlPoints()));
  }
}

bool inSpline(const SE3Splined& spline, double t) {
  return t >= spline.validBegin() && t <= spline.validEnd();
}

// One observation of a frame kept for the problem.
struct FrameObservationUse {
  double t;
  int landmark;
  Eigen::Vector2d pixel;
  bool keyframe;
};

// Whether `frame` is a keyframe of the map (its id names a keyframe taken
// from this frame).
bool isKeyframeOfMap(const FrameRecord& frame, const JointInputs& in) {
  return frame.keyframe && frame.keyframe_id >= 0 &&
         std::size_t(frame.keyframe_id) < in.map_W->keyframes().size() &&
         in.map_W->keyframe(frame.keyframe_id).frame_index == frame.index;
}

// Calls visit(landmark, pixel) for what `frame` saw: a keyframe's
// observations in the map (those of its own pose plus the sightings recorded
// from a track's detection, which the front-end's per-frame list lacks
// because the landmark did not exist yet), otherwise the frame's tracked
// landmarks.
template <typename Visit>
void forEachObservationOf(const FrameRecord& frame, bool keyframe_of_map, const JointInputs& in,
                          Visit&& visit) {
  if (keyframe_of_map) {
    for (const KeyframeObservation& o : in.map_W->keyframe(frame.keyframe_id).observations) {
      visit(o.landmark_id, o.pixel);
    }
    return;
  }
  for (const FrameObservation& o : in.frontend->observationsOfFrame(frame.index)) {
    visit(o.landmark, Eigen::Vector2d(o.u, o.v));
  }
}

// RMS over the kept tie points of their residual at the solved values, on
// the ground: the factor's (u_pred - u) / f and y_U / z_U times the range.
void tieResidualsOnGround(const std::vector<const JointTiePoint*>& ties, const std::vector<bool>& keep,
                          const JointInputs& in, const JointResult& solved, double& across_m,
                          double& along_m) {
  const PushbroomCamera camera(solved.uhi_intrinsics ? withIntrinsics(in.uhi_camera, *solved.uhi_intrinsics)
                                                     : in.uhi_camera);
  const SE3Splined& spline = solved.spline;
  double sum_across = 0.0, sum_along = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < ties.size(); ++i) {
    if (!keep[i]) continue;
    const JointTiePoint& tie = *ties[i];
    const double t_line = tie.t_recorded + solved.time_offset_s;
    const double t_reference = tie.t_recorded + in.time_offset_start_s;
    if (t_line < spline.validBegin() || t_line > spline.validEnd()) continue;
    const Eigen::Vector3d p_W =
        in.surface_trajectory != nullptr
            ? Eigen::Vector3d(spline.pose(t_reference) *
                              (in.surface_trajectory->pose(t_reference).inverse() * tie.p_W))
            : tie.p_W;
    const SE3d T_W_U = spline.pose(t_line) * solved.T_C_U;
    const Eigen::Vector3d p_U = T_W_U.inverse() * p_W;
    const Eigen::Vector2d predicted = camera.project(p_U);
    const double range = p_U.norm();
    sum_across += std::pow((predicted.x() - tie.sample) / camera.parameters().f * range, 2);
    sum_along += std::pow(predicted.y() * range, 2);
    ++n;
  }
  across_m = n > 0 ? std::sqrt(sum_across / double(n)) : 0.0;
  along_m = n > 0 ? std::sqrt(sum_along / double(n)) : 0.0;
}

// The intrinsics' 1-sigma from the joint covariance over [T_C_U (6), d (1),
// the free intrinsics], and the ones the survey cannot separate: a
// correlation above options.inseparable_correlation with a component of
// T_C_U or d (cx against the rotation about the line's normal shifts every
// sample alike over a flat seabed), and the ones it hardly determines: a
// 1-sigma hardly below the prior's.
void checkIntrinsics(const Eigen::MatrixXd& covariance, const JointInputs& in, const JointOptions& options,
                     JointResult& result) {
  constexpr int kOthers = 7;
  std::array<double, PushbroomCamera::kNumIntrinsics> sigma{};
  int column = kOthers;
  for (int i = 0; i < PushbroomCamera::kNumIntrinsics; ++i) {
    const double prior = in.uhi_intrinsics_sigma[std::size_t(i)];
    if (!(prior > 0.0)) continue;  // held: no column, 0 sigma
    const double variance = std::max(0.0, covariance(column, column));
    sigma[std::size_t(i)] = std::sqrt(variance);
    std::ostringstream reason;
    double worst = 0.0;
    int worst_component = -1;
    for (int c = 0; c < kOthers; ++c) {
      const double denominator = std::sqrt(variance * std::max(0.0, covariance(c, c)));
      if (!(denominator > 0.0)) continue;
      const double correlation = covariance(column, c) / denominator;
      if (std::abs(correlation) > std::abs(worst)) {
        worst = correlation;
        worst_component = c;
      }
    }
    const std::string name = std::string("uhi_camera.") + kIntrinsicNames[i];
    if (worst_component >= 0 && std::abs(worst) > options.inseparable_correlation) {
      reason << name << " cannot be separated from " << kExtrinsicComponentNames[worst_component]
             << " on this survey (correlation " << worst << "); it stays close to survey.yaml's value";
      result.inseparable_intrinsics.push_back(reason.str());
    } else if (sigma[std::size_t(i)] > options.weak_fraction_of_prior * prior) {
      // Not tied to T_C_U or d above the threshold: the data simply say
      // little about it (k2 over a line's few hundred pixels of r^4), so the
      // warning says that, not that it trades against the extrinsic.
      reason << name << " is hardly determined by this survey (its 1-sigma " << sigma[std::size_t(i)]
             << " is more than " << options.weak_fraction_of_prior << " of the prior's " << prior
             << "); it stays close to survey.yaml's value";
      result.inseparable_intrinsics.push_back(reason.str());
    }
    ++column;
  }
  result.uhi_intrinsics_sigma = sigma;
}

}  // namespace

std::string JointResult::summary() const {
  std::ostringstream out;
  out << "joint problem: " << spline.numControlPoints() << " spline control points (knots every "
      << spline.dt() << " s), " << landmarks_W.size() << " landmarks, " << frames << " frames\n"
      << "  factors: " << reprojection_factors << " reprojections (" << keyframe_reprojection_factors
      << " of keyframes, " << gated_observations
      << " observations beyond the start gate left out), " << ins_position_factors
      << " INS positions, " << ins_attitude_factors << " INS attitudes, " << tie_inliers
      << " tie points (" << tie_outliers << " outliers removed, " << tie_points_outside_spline
      << " outside the spline), " << smoothness_factors << " smoothness\n";
  if (rewindows > 0) {
    out << "  d moved beyond the tie factors' window: the problem was built again around it " << rewindows
        << " time(s)\n";
  }
  if (!solved) {
    out << "  not solved\n";
  } else {
    out << "  first solve: " << first_solve.toString().substr(0, first_solve.toString().find('\n'))
        << "\n  final solve: " << last_solve.toString() << "\n";
    const Eigen::Vector3d rotation_vector =
        Eigen::AngleAxisd(T_C_U.q).angle() * Eigen::AngleAxisd(T_C_U.q).axis();
    out << "  T_C_U: rotation " << (rotation_vector * kRadToDeg).transpose() << " deg (rotation vector), "
        << "translation " << T_C_U.t.transpose() << " m; d = " << time_offset_s * 1000.0 << " ms\n";
    if (sigma_rotation_deg && sigma_translation_m && time_offset_sigma_s) {
      out << "  1-sigma: rotation " << sigma_rotation_deg->transpose() << " deg, translation "
          << (*sigma_translation_m * 1000.0).transpose() << " mm, d " << *time_offset_sigma_s * 1000.0
          << " ms (covariance " << seconds_covariance << " s)\n";
    }
    if (uhi_intrinsics) {
      out << "  UHI intrinsics: f " << (*uhi_intrinsics)[0] << ", cx " << (*uhi_intrinsics)[1] << ", k1 "
          << (*uhi_intrinsics)[2] << ", k2 " << (*uhi_intrinsics)[3];
      if (uhi_intrinsics_sigma) {
        out << " (1-sigma " << (*uhi_intrinsics_sigma)[0] << ", " << (*uhi_intrinsics_sigma)[1] << ", "
            << (*uhi_intrinsics_sigma)[2] << ", " << (*uhi_intrinsics_sigma)[3] << ")";
      }
      out << "\n";
    }
    out << "  tie point residuals on the ground (RMS over the inliers): "
        << rms_tie_across_m * 1000.0 << " mm across the line, " << rms_tie_along_m * 1000.0
        << " mm along it\n";
  }
  for (const std::string& component : weakly_determined) {
    out << "  weakly determined by this survey: " << component << "\n";
  }
  for (const std::string& warning : inseparable_intrinsics) out << "  warning: " << warning << "\n";
  for (const std::string& warning : warnings) out << "  warning: " << warning << "\n";
  return out.str();
}

JointResult solveJointProblem(const JointInputs& in, const JointOptions& options) {
  options.validate();
  checkInputs(in);
  JointResult result;
  result.spline = in.spline;
  result.T_C_U = in.T_C_U_start;
  result.time_offset_s = in.time_offset_start_s;
  const SE3Splined& spline = in.spline;
  const SplineTiming timing = SplineTiming::of(spline);
  // One camera for the millions of reprojection factors (and their cost functions).
  const auto shared_rgb = std::make_shared<const PinholeRadtanCamera>(in.rgb_camera);
  const PinholeRadtanCamera& rgb = *shared_rgb;

  // Cross-modal tie points first: without enough of them nothing is solved.
  std::vector<const JointTiePoint*> ties;
  result.tie_points_given = int(in.tie_points.size());
  for (const JointTiePoint& tie : in.tie_points) {
    const double t = tie.t_recorded + in.time_offset_start_s;
    const bool in_surface_trajectory =
        in.surface_trajectory == nullptr || inSpline(*in.surface_trajectory, t);
    if (!inSpline(spline, t) || !in_surface_trajectory || !tie.p_W.allFinite() ||
        !std::isfinite(tie.sample)) {
      ++result.tie_points_outside_spline;
      continue;
    }
    ties.push_back(&tie);
  }
  if (int(ties.size()) < options.min_tie_points) {
    result.warnings.push_back("only " + std::to_string(ties.size()) +
                              " usable cross-modal tie points (need " +
                              std::to_string(options.min_tie_points) +
                              "): the joint problem is not solved");
    return result;
  }

  // Frame observations within the spline and the start gate.
  std::vector<FrameObservationUse> observations;
  std::unordered_map<int, int> seen_by;  // landmark -> frames
  std::vector<double> posed_frame_times;
  for (const FrameRecord& frame : in.frontend->frames) {
    if (!frame.posed || frame.index < 0 || std::size_t(frame.index) >= in.frame_times->size()) continue;
    const double t = (*in.frame_times)[std::size_t(frame.index)];
    if (!inSpline(spline, t)) continue;
    const SE3d T_C_W = spline.pose(t).inverse();
    int used = 0;
    const bool is_keyframe = isKeyframeOfMap(frame, in);
    forEachObservationOf(frame, is_keyframe, in, [&](int id, const Eigen::Vector2d& pixel) {
      if (id < 0 || std::size_t(id) >= in.map_W->landmarks().size()) return;
      const Landmark& landmark = in.map_W->landmark(id);
      if (!landmark.valid) return;
      const Eigen::Vector3d p_C = T_C_W * landmark.p_F;
      if (p_C.z() <= 0.0 || (rgb.project(p_C) - pixel).norm() > options.start_gate_px) {
        ++result.gated_observations;
        return;
      }
      observations.push_back({t, id, pixel, is_keyframe});
      ++seen_by[id];
      ++used;
    });
    if (used > 0) posed_frame_times.push_back(t);
  }
  result.frames = int(posed_frame_times.size());

  Values values;
  for (int j = 0; j < spline.numControlPoints(); ++j) {
    const SE3d& T = spline.controlPoints()[std::size_t(j)];
    values.insertPose(S(std::uint64_t(j)), T.q, T.t);
  }
  values.insertPose(E(0), in.T_C_U_start.q, in.T_C_U_start.t);
  values.insertScalar(D(0), in.time_offset_start_s);
  const bool estimates_intrinsics = in.estimatesUhiIntrinsics();
  const PushbroomCamera uhi_prior(in.uhi_camera);
  if (estimates_intrinsics) {
    const auto& start = in.uhi_intrinsics_start ? *in.uhi_intrinsics_start : uhi_prior.intrinsics();
    values.insertVector(K(0), Eigen::Vector4d(start[0], start[1], start[2], start[3]));
  }
  for (const auto& [id, count] : seen_by) {
    if (count < 2) continue;
    values.insertPoint(L(std::uint64_t(id)), in.map_W->landmark(id).p_F);
  }

  const NoiseModel keyframe_pixel_noise = NoiseModel::isotropic(2, options.pixel_sigma_px);
  const NoiseModel other_frame_pixel_noise =
      NoiseModel::isotropic(2, options.pixel_sigma_px * options.other_frame_sigma_factor);
  const RobustLoss huber = RobustLoss::huber(options.huber_sigmas);
  const InsNoise& ins_noise = in.ins_noise;
  const NoiseModel position_noise = NoiseModel::fromSigmas(
      ins_noise.position_correlation_factor *
      Eigen::Vector3d(ins_noise.sigma_horizontal_m, ins_noise.sigma_horizontal_m, ins_noise.sigma_depth_m));
  const NoiseModel attitude_noise = NoiseModel::fromSigmas(
      in.ins->hasAttitude()
          ? ins_noise.sigma_attitude_rad
          : Eigen::Vector3d(ins_noise.assumed_level_sigma_rad, ins_noise.assumed_level_sigma_rad,
                            ins_noise.assumed_heading_sigma_rad));
  const double dt2 = spline.dt() * spline.dt();
  Eigen::Matrix<double, 6, 1> smoothness_sigmas;
  smoothness_sigmas << Eigen::Vector3d::Constant(options.sigma_linear_acceleration * dt2),
      Eigen::Vector3d::Constant(options.sigma_angular_acceleration * dt2);
  const NoiseModel smoothness_noise = NoiseModel::fromSigmas(smoothness_sigmas);

  // Where the frames hold a control point weakly it gets the smoothness
  // prior: fewer than min_frames_in_support posed frames in its support, or
  // less than one frame's worth of their basis weight (a frame spreads a
  // weight of 1 over its segment's four control points). The second
  // matters past the last posed frame: the spline's last segment may reach
  // most of a knot interval beyond it, and there the last control point
  // moves the poses by at most u^3/6 of itself, so the frames barely hold
  // it and one INS fix (decimetres of noise) placed it, with the scan lines
  // posed there, decimetres off.
  const int spline_points = spline.numControlPoints();
  std::vector<int> frames_in_support(std::size_t(spline_points), 0);
  std::vector<double> frame_weight(std::size_t(spline_points), 0.0);
  for (double t : posed_frame_times) {
    const SplineSegment segment = timing.segmentAt(t);
    const int i = segment.first_control_point;
    for (int j = i; j < i + 4; ++j) ++frames_in_support[std::size_t(j)];
    const std::array<double, 4> weights = uniformCubicBasis(segment.u);
    for (int k = 0; k < 4; ++k) frame_weight[std::size_t(i + k)] += weights[std::size_t(k)];
  }
  auto thin = [&](int j) {
    return frames_in_support[std::size_t(j)] < options.min_frames_in_support ||
           frame_weight[std::size_t(j)] < options.min_frame_weight_in_support;
  };
  // The factor at j ties j - 1, j and j + 1: it is added wherever one of
  // them is thin, so the first and last control points are held too.
  std::vector<int> smoothed;
  for (int j = 1; j + 1 < spline_points; ++j) {
    if (thin(j - 1) || thin(j) || thin(j + 1)) smoothed.push_back(j);
  }

  auto buildGraph = [&](const std::vector<bool>& keep_tie, std::vector<std::size_t>* tie_factor_index) {
    FactorGraph graph;
    result.reprojection_factors = result.keyframe_reprojection_factors = 0;
    result.ins_position_factors = result.ins_attitude_factors = result.smoothness_factors = 0;
    for (const FrameObservationUse& o : observations) {
      if (!values.contains(L(std::uint64_t(o.landmark)))) continue;
      graph.emplace<SplineReprojectionFactor>(
          timing, o.t, L(std::uint64_t(o.landmark)), o.pixel, shared_rgb,
          o.keyframe ? keyframe_pixel_noise : other_frame_pixel_noise, huber);
      ++result.reprojection_factors;
      if (o.keyframe) ++result.keyframe_reprojection_factors;
    }
    const std::vector<InsBodyFix>& fixes = in.ins->fixes();
    for (std::size_t k = 0; k < fixes.size(); ++k) {
      if (in.excluded_fixes.count(int(k)) != 0 || !inSpline(spline, fixes[k].t)) continue;
      graph.emplace<SplineInsPositionFactor>(timing, fixes[k].t, fixes[k].p_W_B, in.T_B_C,
                                             position_noise);
      ++result.ins_position_factors;
      graph.emplace<SplineInsAttitudeFactor>(timing, fixes[k].t, fixes[k].q_W_B, in.T_B_C,
                                             attitude_noise);
      ++result.ins_attitude_factors;
    }
    for (const int j : smoothed) {
      graph.emplace<SplineSmoothnessFactor>(std::uint64_t(j), smoothness_noise);
      ++result.smoothness_factors;
    }
    graph.emplace<ExtrinsicPriorFactor>(
        E(0), in.T_C_U_prior,
        ExtrinsicPriorFactor::noiseFromSigmas(in.sigma_rotation_deg, in.sigma_translation_m));
    graph.emplace<TimeOffsetPriorFactor>(D(0), in.time_offset_prior_s,
                                         NoiseModel::isotropic(1, in.time_offset_sigma_s));
    if (estimates_intrinsics) {
      graph.emplace<PushbroomIntrinsicsPriorFactor>(K(0), uhi_prior.intrinsics(), in.uhi_intrinsics_sigma);
    }
    if (tie_factor_index != nullptr) tie_factor_index->assign(ties.size(), std::size_t(-1));
    for (std::size_t i = 0; i < ties.size(); ++i) {
      if (!keep_tie[i]) continue;
      const JointTiePoint& tie = *ties[i];
      const double range = tie.range_m > 0.0 ? tie.range_m : kDefaultRangeM;
      const double sigma_across = options.sigma_match_m / range;
      const double sigma_along =
          (options.sigma_match_along_m > 0.0 ? options.sigma_match_along_m : options.sigma_match_m) /
          range;
      const Eigen::Vector2d sigmas(in.uhi_camera.f * sigma_across, sigma_along);
      const PushbroomObservation observation{tie.t_recorded, tie.sample};
      const NoiseModel noise = NoiseModel::fromSigmas(sigmas);
      const RobustLoss loss = RobustLoss::cauchy(options.tie_robust_scale);
      std::size_t index = 0;
      if (in.surface_trajectory != nullptr) {
        const double t_reference = tie.t_recorded + in.time_offset_start_s;
        const Eigen::Vector3d p_C = in.surface_trajectory->pose(t_reference).inverse() * tie.p_W;
        if (estimates_intrinsics) {
          index = graph.emplace<PushbroomCameraPointFactor>(timing, in.time_offset_start_s, E(0), D(0), K(0),
                                                            t_reference, p_C, observation, in.uhi_camera,
                                                            noise, loss);
        } else {
          index = graph.emplace<PushbroomCameraPointFactor>(timing, in.time_offset_start_s, E(0), D(0),
                                                            t_reference, p_C, observation,
                                                            in.uhi_camera, noise, loss);
        }
      } else {
        index = graph.emplace<PushbroomLineFactor>(timing, in.time_offset_start_s, E(0), D(0),
                                                   tie.p_W, observation, in.uhi_camera, noise, loss);
      }
      if (tie_factor_index != nullptr) (*tie_factor_index)[i] = index;
    }
    return graph;
  };

  SolverOptions solver;
  solver.linear_solver = SolverOptions::LinearSolver::sparse_schur;
  solver.max_iterations = options.max_iterations;
  solver.num_threads = options.num_threads;
  solver.function_tolerance = 1e-7;
  GraphProblemOptions problem_options;
  // The tie factors' control-point window covers d within half a knot
  // interval of the start (PushbroomLineFactor): d is bounded inside it, and
  // the caller re-windows (builds the problem again) between rounds.
  const double reach = 0.45 * spline.dt();
  problem_options.bounds.push_back(
      {D(0), 0, in.time_offset_start_s - reach, in.time_offset_start_s + reach});
  const std::vector<int> held_intrinsics = PushbroomIntrinsicsPriorFactor::heldParameters(in.uhi_intrinsics_sigma);
  if (estimates_intrinsics && !held_intrinsics.empty()) {
    problem_options.constant_components[K(0)] = held_intrinsics;
  }

  std::vector<bool> keep(ties.size(), true);
  {
    std::vector<std::size_t> tie_factor;
    const FactorGraph graph = buildGraph(keep, &tie_factor);
    GraphProblem problem(graph, values, problem_options);
    result.first_solve = solve(problem, solver);
    if (!result.first_solve.usable) {
      result.warnings.push_back("the first solve failed (" + result.first_solve.reason +
                                "): the sequential result is kept");
      return result;
    }
    const std::vector<std::size_t> beyond = factorsBeyondLossScale(
        problem, options.num_threads > 0 ? options.num_threads : threadBudget());
    std::unordered_map<std::size_t, std::size_t> tie_of_factor;
    for (std::size_t i = 0; i < tie_factor.size(); ++i) tie_of_factor[tie_factor[i]] = i;
    for (std::size_t index : beyond) {
      const auto found = tie_of_factor.find(index);
      if (found == tie_of_factor.end()) continue;
      keep[found->second] = false;
      ++result.tie_outliers;
    }
  }
  result.tie_inliers = int(std::count(keep.begin(), keep.end(), true));
  if (result.tie_inliers < options.min_tie_points) {
    result.warnings.push_back("only " + std::to_string(result.tie_inliers) +
                              " tie points are inliers: the sequential result is kept");
    return result;
  }

  const FactorGraph graph = buildGraph(keep, nullptr);
  GraphProblem problem(graph, values, problem_options);
  result.last_solve = solve(problem, solver);
  if (!result.last_solve.usable) {
    result.warnings.push_back("the final solve failed (" + result.last_solve.reason +
                              "): the sequential result is kept");
    return result;
  }
  result.solved = true;
  std::vector<SE3d> control_points;
  for (int j = 0; j < spline.numControlPoints(); ++j) {
    control_points.emplace_back(values.poseRotation(S(std::uint64_t(j))).normalized(),
                                values.poseTranslation(S(std::uint64_t(j))));
  }
  result.spline = SE3Splined(spline.t0(), spline.dt(), std::move(control_points));
  result.T_C_U = SE3d(values.poseRotation(E(0)).normalized(), values.poseTranslation(E(0)));
  result.time_offset_s = values.scalar(D(0));
  if (estimates_intrinsics) {
    const Eigen::VectorXd k = values.vector(K(0));
    result.uhi_intrinsics = std::array<double, PushbroomCamera::kNumIntrinsics>{k[0], k[1], k[2], k[3]};
  }
  if (std::abs(result.time_offset_s - in.time_offset_start_s) > 0.99 * reach) {
    if (options.max_rewindows > 0) {
      // Built again around the new d, from this result (see the header).
      JointInputs next = in;
      next.spline = result.spline;
      next.T_C_U_start = result.T_C_U;
      next.time_offset_start_s = result.time_offset_s;
      next.uhi_intrinsics_start = result.uhi_intrinsics;
      JointOptions fewer = options;
      --fewer.max_rewindows;
      JointResult again = solveJointProblem(next, fewer);
      if (again.solved) {
        ++again.rewindows;
        return again;
      }
      result.warnings.push_back("the problem built again around d = " +
                                std::to_string(result.time_offset_s * 1000.0) + " ms was not solved (" +
                                (again.warnings.empty() ? std::string("no reason given") : again.warnings.front()) +
                                "): this window's result is kept");
    }
    result.time_offset_at_bound = true;
    result.warnings.push_back("d reached the bound of this round's window (" +
                              std::to_string(reach * 1000.0) +
                              " ms from its start): another round is needed");
  }
  tieResidualsOnGround(ties, keep, in, result, result.rms_tie_across_m, result.rms_tie_along_m);
  for (const auto& [id, count] : seen_by) {
    if (values.contains(L(std::uint64_t(id)))) {
      result.landmarks_W.emplace_back(id, values.point(L(std::uint64_t(id))));
    }
  }
  // 1-sigma of T_C_U and d with every other variable free.
  const auto start = std::chrono::steady_clock::now();
  try {
    CovarianceOptions covariance_options;
    covariance_options.num_threads = options.num_threads;
    // Only T_C_U and d are asked for: eliminate the landmarks by their Schur
    // complement (the reduced system is the spline, T_C_U and d).
    covariance_options.algorithm = CovarianceOptions::Algorithm::landmark_schur;
    std::vector<Key> asked{E(0), D(0)};
    if (estimates_intrinsics) asked.push_back(K(0));
    const Eigen::MatrixXd covariance = jointMarginalCovariance(problem, asked, covariance_options);
    const Eigen::Matrix3d R_C_U = result.T_C_U.q.toRotationMatrix();
    const Eigen::Matrix3d translation_C = R_C_U * covariance.topLeftCorner<3, 3>() * R_C_U.transpose();
    result.sigma_translation_m = translation_C.diagonal().cwiseMax(0.0).cwiseSqrt();
    result.sigma_rotation_deg = Eigen::Vector3d(
        covariance.block<3, 3>(3, 3).diagonal().cwiseMax(0.0).cwiseSqrt() * kRadToDeg);
    result.time_offset_sigma_s = std::sqrt(std::max(0.0, covariance(6, 6)));
    const char* axes = "xyz";
    for (int i = 0; i < 3; ++i) {
      if ((*result.sigma_rotation_deg)[i] > options.weak_fraction_of_prior * in.sigma_rotation_deg) {
        result.weakly_determined.push_back(std::string("T_C_U rotation about U's ") + axes[i]);
      }
    }
    for (int i = 0; i < 3; ++i) {
      if ((*result.sigma_translation_m)[i] > options.weak_fraction_of_prior * in.sigma_translation_m) {
        result.weakly_determined.push_back(std::string("T_C_U translation along C's ") + axes[i]);
      }
    }
    if (*result.time_offset_sigma_s > options.weak_fraction_of_prior * in.time_offset_sigma_s) {
      result.weakly_determined.push_back("the time offset d");
    }
    if (estimates_intrinsics) checkIntrinsics(covariance, in, options, result);
  } catch (const std::exception& error) {
    result.warnings.push_back(std::string("no covariance for T_C_U and d: ") + error.what());
  }
  result.seconds_covariance =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace hsmap
