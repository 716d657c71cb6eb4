#include "pipelines/joint/joint_solution.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

namespace hsmap {

std::vector<JointTiePoint> jointTiePoints(const std::vector<ExtrinsicTiePoint>& found,
                                          const std::vector<double>& line_times) {
  std::vector<JointTiePoint> ties;
  ties.reserve(found.size());
  for (const ExtrinsicTiePoint& tie : found) {
    // The recorded time at the tie's continuous line position, between the
    // two lines around it.
    const double below = std::floor(tie.line_position);
    const double alpha = tie.line_position - below;
    if (!(below >= 0.0) || below + (alpha > 0.0 ? 1.0 : 0.0) >= double(line_times.size())) continue;
    const std::size_t a = std::size_t(below);
    const double t_recorded =
        alpha > 0.0 ? (1.0 - alpha) * line_times[a] + alpha * line_times[a + 1] : line_times[a];
    ties.push_back({tie.line, t_recorded, tie.sample, tie.range_m, tie.p_W});
  }
  return ties;
}

// The georef result with every frame and scan line posed from the spline
// where it is valid (elsewhere the sequential poses stay).
GeorefResult posedFromSpline(const GeorefResult& sequential, const JointResult& joint,
                             const std::vector<double>& line_times) {
  GeorefResult result = sequential;
  result.variant = "joint";
  const SE3Splined& spline = joint.spline;
  auto inSpline = [&](double t) { return t >= spline.validBegin() && t <= spline.validEnd(); };
  for (GeorefFramePose& frame : result.frames) {
    if (inSpline(frame.t)) frame.T_W_C = spline.pose(frame.t);
  }
  for (GeorefLinePose& line : result.lines) {
    const double t = line_times[std::size_t(line.line)] + joint.time_offset_s;
    line.t = t;
    if (inSpline(t)) {
      line.T_W_U = spline.pose(t) * joint.T_C_U;
    } else {
      // Outside the spline: the sequential camera pose, with the new extrinsic.
      line.T_W_U = line.T_W_U * sequential.T_C_U.inverse() * joint.T_C_U;
    }
  }
  result.T_C_U = joint.T_C_U;
  result.time_offset_s = joint.time_offset_s;
  result.landmarks_W.clear();
  for (const auto& [id, p_W] : joint.landmarks_W) result.landmarks_W.push_back(p_W);
  return result;
}

// The rigid motion G that brings the solved trajectory onto the one the
// surface was made with (least squares over the frames' positions,
// Eigen::umeyama without scale). The solve may settle the whole trajectory
// a few centimetres away (its absolute position is the INS's, to
// decimetres); T_C_U and d do not depend on that, but the scan lines must be
// cast onto the mesh in the mesh's own frame.
Sim3 ontoSurfaceFrame(const SE3Splined& solved, const SE3Splined& surface,
                      const std::vector<TimedPose>& frames) {
  Eigen::Matrix3Xd from(3, Eigen::Index(frames.size())), to(3, Eigen::Index(frames.size()));
  Eigen::Index n = 0;
  for (const TimedPose& frame : frames) {
    if (frame.t < solved.validBegin() || frame.t > solved.validEnd()) continue;
    from.col(n) = solved.pose(frame.t).t;
    to.col(n) = surface.pose(frame.t).t;
    ++n;
  }
  if (n < 3) return Sim3::identity();
  const Eigen::Matrix4d G = Eigen::umeyama(from.leftCols(n), to.leftCols(n), true);
  const double scale = G.topLeftCorner<3, 3>().col(0).norm();
  return Sim3(scale, Eigen::Quaterniond(Eigen::Matrix3d(G.topLeftCorner<3, 3>() / scale)).normalized(),
              G.topRightCorner<3, 1>());
}

JointResult inSurfaceFrame(JointResult joint, const Sim3& G) {
  std::vector<SE3d> control_points;
  for (const SE3d& T : joint.spline.controlPoints()) control_points.push_back(G.transformPose(T));
  joint.spline = SE3Splined(joint.spline.t0(), joint.spline.dt(), std::move(control_points));
  for (auto& [id, p_W] : joint.landmarks_W) p_W = G.apply(p_W);
  joint.T_C_U.t *= G.scale();
  if (joint.sigma_translation_m) *joint.sigma_translation_m *= G.scale();
  return joint;
}

// The sparse map of the sequential result with the joint keyframe poses and
// landmarks, for the surface stage.
GeorefResult withJointMap(GeorefResult posed, const JointResult& joint) {
  const SE3Splined& spline = joint.spline;
  for (const Keyframe& keyframe : posed.map_W.keyframes()) {
    if (keyframe.t >= spline.validBegin() && keyframe.t <= spline.validEnd()) {
      posed.map_W.keyframe(keyframe.id).T_F_C = spline.pose(keyframe.t);
    }
  }
  for (const auto& [id, p_W] : joint.landmarks_W) posed.map_W.landmark(id).p_F = p_W;
  return posed;
}

RunCalibration jointCalibration(const JointResult& joint, int round,
                                const std::optional<MapPlacement>& placement) {
  RunCalibration calibration;
  calibration.variant = "joint";
  calibration.T_C_U.rotation = joint.T_C_U.q;
  calibration.T_C_U.translation_m = joint.T_C_U.t;
  calibration.sigma_rotation_deg = joint.sigma_rotation_deg;
  calibration.sigma_translation_m = joint.sigma_translation_m;

  calibration.time_offset_s = joint.time_offset_s;
  calibration.time_offset_sigma_s = joint.time_offset_sigma_s;
  calibration.warnings.push_back("T_C_U and time_offset_s estimated by the joint problem (round " +
                                 std::to_string(round) + ", " + std::to_string(joint.tie_inliers) +
                                 " cross-modal tie points)");
  for (const std::string& component : joint.weakly_determined) {
    calibration.warnings.push_back("observability: " + component +
                                   " is weakly determined by this survey (its 1-sigma is more "
                                   "than half the prior's); it stays close to survey.yaml's guess");
  }
  if (joint.uhi_intrinsics) {
    const auto& k = *joint.uhi_intrinsics;
    UhiCameraEstimate camera;
    camera.f = k[0];
    camera.cx = k[1];
    camera.distortion = {k[2], k[3]};
    if (joint.uhi_intrinsics_sigma) {
      const auto& sigma = *joint.uhi_intrinsics_sigma;
      camera.sigma.f = sigma[0];
      camera.sigma.cx = sigma[1];
      camera.sigma.distortion = {sigma[2], sigma[3]};
    } else {
      calibration.warnings.push_back("no covariance for uhi_camera: its sigmas are written as 0");
    }
    calibration.uhi_camera = camera;
    calibration.warnings.push_back("uhi_camera estimated by the joint problem with T_C_U and d");
    for (const std::string& warning : joint.inseparable_intrinsics) calibration.warnings.push_back(warning);
  }
  if (placement) addMapScaleUncertainty(calibration, *placement);
  for (const std::string& warning : joint.warnings) calibration.warnings.push_back(warning);
  return calibration;
}

}  // namespace hsmap
