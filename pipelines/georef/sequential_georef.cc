#include "pipelines/georef/sequential_georef.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/survey/ins_body_track.h"
#include "pipelines/georef/camera_trajectory.h"
#include "pipelines/georef/frame_reposer.h"
#include "pipelines/georef/ins_alignment.h"
#include "pipelines/georef/ins_similarity.h"
#include "pipelines/georef/scan_line_poses.h"

namespace hsmap {
namespace {

constexpr double kDegreesToRadians = M_PI / 180.0;

// The frames the front-end posed, in time order.
struct VisionFrames {
  std::vector<double> times;
  std::vector<SE3d> T_X_C;       // in F, then in W
  std::vector<int> record;       // index into FrontendResult::frames
};

VisionFrames posedFrames(const FrontendResult& frontend) {
  VisionFrames frames;
  for (std::size_t i = 0; i < frontend.frames.size(); ++i) {
    const FrameRecord& f = frontend.frames[i];
    if (!f.posed) continue;
    if (!frames.times.empty() && !(f.t > frames.times.back())) continue;  // equal stamps: keep the first
    frames.times.push_back(f.t);
    frames.T_X_C.push_back(f.T_F_C);
    frames.record.push_back(int(i));
  }
  return frames;
}

// Keyframes of each map segment, in time order, to find the one nearest a time.
class KeyframesBySegment {
 public:
  explicit KeyframesBySegment(const VisualMap& map) {
    for (const Keyframe& k : map.keyframes()) by_segment_[k.segment].emplace_back(k.t, k.id);
    for (auto& [segment, list] : by_segment_) std::sort(list.begin(), list.end());
  }
  // The keyframe of `segment` nearest to t, or -1.
  int nearest(int segment, double t) const {
    const auto found = by_segment_.find(segment);
    if (found == by_segment_.end() || found->second.empty()) return -1;
    const auto& list = found->second;
    const auto after = std::lower_bound(list.begin(), list.end(), std::make_pair(t, -1));
    if (after == list.begin()) return after->second;
    if (after == list.end()) return list.back().second;
    const auto before = std::prev(after);
    return (t - before->first <= after->first - t) ? before->second : after->second;
  }

 private:
  std::map<int, std::vector<std::pair<double, int>>> by_segment_;
};

// The segment of the posed frame nearest to t.
int segmentAt(const VisionFrames& frames, const FrontendResult& frontend, double t) {
  const auto after = std::lower_bound(frames.times.begin(), frames.times.end(), t);
  std::size_t j = std::size_t(after - frames.times.begin());
  if (j == frames.times.size()) --j;
  if (j > 0 && t - frames.times[j - 1] < frames.times[j] - t) --j;
  return frontend.frames[std::size_t(frames.record[j])].segment;
}

// The map's scale and placement by maximum likelihood on the fixes the
// adjustment kept, with the noise survey.yaml states (ins_similarity.h). The
// adjustment's position sigmas are inflated for the INS's correlated wander
// (GeorefOptions::ins_correlation_time_s), which is right for the shape but
// weighs the attitude (or its level prior) against the positions otherwise
// than the survey states; the shape is kept and only this similarity moves
// the whole map, so its scale is what the INS floor describes. Returns the
// similarity's 1-sigma and the correction applied.
MapPlacement placeMapOnIns(VisualMap& map, const std::vector<InsFixLink>& links,
                           const std::vector<RejectedFix>& rejected, const InsBodyTrack& ins,
                           const SE3d& T_B_C, const InsNoise& noise) {
  std::vector<CameraAtFix> cameras;
  for (const InsFixLink& link : links) {
    const bool left_out = std::any_of(rejected.begin(), rejected.end(),
                                      [&](const RejectedFix& r) { return r.fix == link.fix; });
    if (!left_out) cameras.push_back({link.fix, map.keyframe(link.keyframe).T_F_C * link.T_K_C});
  }
  SimilarityFit fit;
  try {
    fit = fitMapToIns(cameras, ins, T_B_C, noise, Sim3::identity());
  } catch (const std::invalid_argument& error) {
    throw std::runtime_error(std::string("cannot place the map on the INS: ") + error.what());
  }
  const Sim3& S = fit.S_target_source;
  // What each part of the INS contributes: the same fit on the corrected
  // map without the attitude, and without the depths' precision.
  for (CameraAtFix& camera : cameras) camera.T_X_C = S.transformPose(camera.T_X_C);
  const double without_attitude =
      fitMapToIns(cameras, ins, T_B_C, noise, Sim3::identity(), InsParts::without_attitude)
          .sigma_log_scale;
  const double without_depth =
      fitMapToIns(cameras, ins, T_B_C, noise, Sim3::identity(), InsParts::without_depth)
          .sigma_log_scale;
  for (const Keyframe& k : map.keyframes()) map.keyframe(k.id).T_F_C = S.transformPose(k.T_F_C);
  for (const Landmark& l : map.landmarks()) {
    if (l.valid) map.landmark(l.id).p_F = S.apply(l.p_F);
  }
  MapPlacement placement;
  placement.fixes = int(cameras.size());
  placement.attitude_measured = ins.hasAttitude();
  placement.scale_sigma = fit.sigma_log_scale;
  placement.scale_sigma_without_attitude = without_attitude;
  placement.scale_sigma_without_depth = without_depth;
  placement.rotation_sigma_deg = fit.sigma_rotation_rad / kDegreesToRadians;
  placement.position_sigma_m = fit.sigma_translation;
  placement.correction_scale = S.scale();
  placement.correction_rotation_deg = S.rotation().angularDistance(Eigen::Quaterniond::Identity()) /
                                      kDegreesToRadians;
  // How far the correction moved the map's centroid (where the fixes are).
  placement.correction_translation_m = (S.apply(fit.centroid_source) - fit.centroid_source).norm();
  return placement;
}

}  // namespace

// sqrt(correlation time / median fix interval), at least 1 (georef_options.h).
double insCorrelationFactor(const InsBodyTrack& ins, double correlation_time_s) {
  if (!(correlation_time_s > 0.0) || ins.fixes().size() < 2) return 1.0;
  std::vector<double> intervals;
  for (std::size_t i = 1; i < ins.fixes().size(); ++i) {
    intervals.push_back(ins.fixes()[i].t - ins.fixes()[i - 1].t);
  }
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  return std::sqrt(std::max(1.0, correlation_time_s / intervals[intervals.size() / 2]));
}

InsNoise surveyInsNoise(const Survey& survey, const InsBodyTrack& ins, const GeorefOptions& options) {
  const InsConfig& ins_config = survey.config.ins;
  InsNoise noise;
  noise.sigma_horizontal_m = ins_config.sigma_horizontal_m;
  noise.sigma_depth_m = ins_config.sigma_depth_m;
  noise.position_correlation_factor = insCorrelationFactor(ins, options.ins_correlation_time_s);
  noise.sigma_attitude_rad = Eigen::Vector3d(ins_config.sigma_attitude_deg[0],
                                             ins_config.sigma_attitude_deg[1],
                                             ins_config.sigma_attitude_deg[2]) *
                             kDegreesToRadians;
  return noise;
}

GeorefResult runSequentialGeoref(const Survey& survey, const FrontendResult& frontend,
                                 const GeorefOptions& options, const GeorefProgress& progress) {
  options.validate();
  GeorefResult result;
  result.variant = "sequential";
  const InsBodyTrack ins(survey, options.heading_window_s);
  const InsConfig& ins_config = survey.config.ins;
  const SE3d T_B_C(ins_config.T_B_C.rotation, ins_config.T_B_C.translation_m);

  // 1. The front-end's trajectory onto the INS.
  VisionFrames vision = posedFrames(frontend);
  if (vision.times.size() < 2) {
    throw std::runtime_error("cannot geo-reference: the front-end posed " +
                             std::to_string(vision.times.size()) + " frames (need at least 2)");
  }
  const InsNoise noise = surveyInsNoise(survey, ins, options);
  if (progress) progress("alignment", 0, 1);
  {
    const CameraTrajectory vision_F(vision.times, vision.T_X_C, nullptr, T_B_C,
                                    options.max_vision_gap_s);
    result.alignment = alignVisionToIns(vision_F, ins, T_B_C, noise);
  }
  const InsAlignment& alignment = *result.alignment;
  for (std::size_t k = 0; k < alignment.paired_fixes.size(); ++k) {
    if (alignment.inliers[k]) continue;
    const InsBodyFix& fix = ins.fixes()[std::size_t(alignment.paired_fixes[k])];
    result.rejected_fixes.push_back(
        {alignment.paired_fixes[k], fix.line_number, fix.t, alignment.residuals_m[k], "alignment"});
  }
  const Sim3& S_W_F = alignment.S_W_F;
  VisualMap map = frontend.map;
  for (const Keyframe& k : frontend.map.keyframes()) map.keyframe(k.id).T_F_C = S_W_F.transformPose(k.T_F_C);
  for (const Landmark& l : frontend.map.landmarks()) {
    if (l.valid) map.landmark(l.id).p_F = S_W_F.apply(l.p_F);
  }
  for (SE3d& T : vision.T_X_C) T = S_W_F.transformPose(T);
  const CameraTrajectory vision_W(vision.times, vision.T_X_C, nullptr, T_B_C, options.max_vision_gap_s);
  if (progress) progress("alignment", 1, 1);

  // 2. Bundle adjustment with every fix at its own time.
  const KeyframesBySegment keyframes(map);
  std::vector<InsFixLink> links;
  for (std::size_t k = 0; k < alignment.paired_fixes.size(); ++k) {
    if (!alignment.inliers[k]) continue;
    const int fix = alignment.paired_fixes[k];
    const double t = ins.fixes()[std::size_t(fix)].t;
    const int keyframe = keyframes.nearest(segmentAt(vision, frontend, t), t);
    if (keyframe < 0) continue;
    const SE3d T_K_C = map.keyframe(keyframe).T_F_C.inverse() * vision_W.at(t).T_W_C;
    links.push_back({fix, keyframe, T_K_C});
  }
  std::vector<SE3d> T_W_K_before;
  for (const Keyframe& k : map.keyframes()) T_W_K_before.push_back(k.T_F_C);
  if (progress) progress("bundle adjustment", 0, 1);
  result.bundle = adjustGeoreferencedMap(map, links, ins, T_B_C, noise, survey.config.rgb.camera,
                                         options.bundle, survey.config.rgb.camera_sigma);
  // With rgb.camera_sigma the adjustment estimated the intrinsics: every
  // frame is posed through them, and the later stages use them
  // (georef/calibration.yaml's rgb_camera).
  PinholeRadtanParameters rgb_camera = survey.config.rgb.camera;
  if (result.bundle->intrinsics) {
    const RgbIntrinsicsEstimate& estimate = *result.bundle->intrinsics;
    rgb_camera = estimate.camera;
    result.rgb_camera = estimate;
    if (!estimate.sigma_known) {
      result.warnings.push_back("rgb_camera: no covariance (" + estimate.covariance_error +
                                "): its sigmas are written as 0");
    }
    for (const std::string& warning : estimate.inseparable) result.warnings.push_back(warning);
  }
  const PinholeRadtanCamera camera(rgb_camera);
  for (const RejectedFix& r : result.bundle->rejected) result.rejected_fixes.push_back(r);
  result.placement = placeMapOnIns(map, links, result.bundle->rejected, ins, T_B_C, noise);
  if (const std::string warning = scaleWarning(*result.placement); !warning.empty()) {
    result.warnings.push_back(warning);
  }
  if (progress) progress("bundle adjustment", 1, 1);

  // 3. Every posed frame again, against the adjusted landmarks.
  std::vector<FrameToRepose> to_repose;
  std::vector<std::size_t> repose_slot;  // index into vision.*
  for (std::size_t j = 0; j < vision.times.size(); ++j) {
    const FrameRecord& record = frontend.frames[std::size_t(vision.record[j])];
    if (record.keyframe && record.keyframe_id >= 0) {
      vision.T_X_C[j] = map.keyframe(record.keyframe_id).T_F_C;
      ++result.repose.keyframes;
      continue;
    }
    const int k = keyframes.nearest(record.segment, record.t);
    SE3d prediction = vision.T_X_C[j];
    if (k >= 0) {
      prediction = map.keyframe(k).T_F_C * (T_W_K_before[std::size_t(k)].inverse() * vision.T_X_C[j]);
    }
    to_repose.push_back({record.index, prediction});
    repose_slot.push_back(j);
  }
  const int total = int(to_repose.size());
  const std::vector<Repose> reposed = reposeFrames(
      to_repose, frontend, map, camera, options.pose,
      [&](int done) {
        if (progress) progress("frames", done, total);
      });
  for (std::size_t i = 0; i < reposed.size(); ++i) {
    vision.T_X_C[repose_slot[i]] = reposed[i].T_W_C;
    if (reposed[i].ok) {
      ++result.repose.pnp;
    } else {
      ++result.repose.from_keyframe;
    }
  }
  if (progress) progress("frames", total, total);

  // 4. Every frame and scan line, bridged by the INS where vision has none.
  const CameraTrajectory trajectory(vision.times, vision.T_X_C, &ins, T_B_C, options.max_vision_gap_s);
  const std::vector<double>& times = survey.rgb.times();
  result.frames.reserve(times.size());
  for (std::size_t i = 0; i < times.size(); ++i) {
    const TimedCameraPose pose = trajectory.at(times[i]);
    result.frames.push_back({int(i), times[i], pose.T_W_C, pose.source});
  }
  result.T_C_U = SE3d(survey.config.uhi.T_C_U.rotation, survey.config.uhi.T_C_U.translation_m);
  result.time_offset_s = survey.config.uhi.time_offset_s;
  result.lines = poseScanLines(survey.line_times, trajectory, result.T_C_U, result.time_offset_s);
  for (const Landmark& l : map.landmarks()) {
    if (l.valid) result.landmarks_W.push_back(l.p_F);
  }
  result.map_W = std::move(map);
  if (result.repose.from_keyframe > 0) {
    result.warnings.push_back(std::to_string(result.repose.from_keyframe) +
                              " frames could not be posed by PnP on the adjusted landmarks and "
                              "follow their keyframe instead");
  }
  const int bridged_frames = result.frameCount(PoseSource::ins_bridged) + result.frameCount(PoseSource::held);
  if (bridged_frames > 0) {
    result.warnings.push_back(std::to_string(bridged_frames) +
                              " frames have no vision pose (tracking losses or beyond the "
                              "tracked span) and were bridged by the INS");
  }
  return result;
}

}  // namespace hsmap
