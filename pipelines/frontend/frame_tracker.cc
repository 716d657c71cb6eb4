#include "pipelines/frontend/frame_tracker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/util/median.h"
#include "pipelines/frontend/exposure_compensation.h"
#include "pipelines/frontend/keyframe_policy.h"
#include "pipelines/frontend/landmark_triangulator.h"
#include "pipelines/frontend/tracking_loss_monitor.h"
#include "pipelines/frontend/two_view_initializer.h"

namespace hsmap {

namespace {

constexpr double kDegToRad = M_PI / 180.0;

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double lapMs() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return ms;
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

double& stepMs(FrameRecord& record, FrontendStep step) { return record.ms[std::size_t(step)]; }

Eigen::Vector2d toEigen(const cv::Point2f& p) { return {double(p.x), double(p.y)}; }

}  // namespace

FrameTracker::FrameTracker(const FrontendOptions& options, const PinholeRadtanCamera& camera)
    : options_(options),
      camera_(camera),
      klt_(options, camera.width()),
      detector_(options, camera.width(), camera.height()),
      error_scale_(options.errorScale(camera.width())),
      equaliser_(options, camera.width(), camera.height()) {
  options_.validate();
  pose_options_.ransac_threshold_px = options.pnp_threshold_px * error_scale_;
  pose_options_.ransac_iterations = options.pnp_ransac_iterations;
  pose_options_.pixel_sigma_px = options.pixel_sigma_px * error_scale_;
  pose_options_.huber_scale = options.huber_scale;
  pose_options_.max_iterations = options.refine_max_iterations;
  pose_options_.inlier_threshold_px = options.inlier_threshold_px * error_scale_;
  pose_options_.min_inliers = options.min_pose_inliers;
  pose_options_.solver_threads = options.solver_threads;
  ba_options_.pixel_sigma_px = options.pixel_sigma_px * error_scale_;
  ba_options_.huber_scale = options.huber_scale;
  ba_options_.max_iterations = options.ba_max_iterations;
  ba_options_.max_fixed_keyframes = options.ba_max_fixed_keyframes;
  ba_options_.outlier_px = options.ba_outlier_px * error_scale_;
  ba_options_.solver_threads = options.solver_threads;
}

bool FrameTracker::undistort(const cv::Point2f& pixel, Eigen::Vector2d& normalized) const {
  const auto ray = camera_.unproject(toEigen(pixel));
  if (!ray || !(ray->z() > 0.0)) return false;
  normalized = ray->head<2>() / ray->z();
  return true;
}

void FrameTracker::process(const PrefetchedFrame& frame) {
  records_.emplace_back();
  anchors_.emplace_back();
  last_frame_index_ = frame.index;
  FrameRecord& record = records_.back();
  record.index = frame.index;
  record.t = frame.t;
  stepMs(record, FrontendStep::decode) = frame.decode_ms;
  stepMs(record, FrontendStep::preprocess) = frame.preprocess_ms;
  if (!frame.error.empty()) {
    markLost(record, FrameStatus::undecodable, "undecodable: " + frame.error);
    return;
  }
  if (const auto problem = textureProblem(frame.quality, options_)) {
    markLost(record, FrameStatus::no_texture, *problem);
    return;
  }
  Stopwatch watch;
  const ImagePyramid pyramid = klt_.buildPyramid(frame.gray);
  stepMs(record, FrontendStep::track) += watch.lapMs();
  if (state_ == State::tracking) {
    processTracking(frame, record, pyramid);
  } else {
    processInitialising(frame, record, pyramid);
  }
}

// A frame that cannot be posed: while tracking, bridged up to
// max_bridged_frames, then the segment ends.
void FrameTracker::markLost(FrameRecord& record, FrameStatus status, const std::string& reason) {
  record.status = status;
  record.posed = false;
  loss_reasons_.emplace(record.index, reason);
  if (state_ == State::tracking) {
    ++failed_frames_;
    if (failed_frames_ > options_.max_bridged_frames) endSegment();
  }
}

void FrameTracker::sortFrameObservationsFrom(std::size_t first) {
  std::sort(frame_observations_.begin() + std::ptrdiff_t(first), frame_observations_.end(),
            [](const FrameObservation& a, const FrameObservation& b) { return a.landmark < b.landmark; });
}

void FrameTracker::endSegment() {
  state_ = State::initialising;
  tracks_.clear();
  have_reference_ = false;
  buffer_.clear();
  have_motion_ = false;
  failed_frames_ = 0;
  last_keyframe_ = -1;
}

SE3d FrameTracker::predictPose(double t) const {
  if (!have_motion_) return last_T_S_C_;
  return last_T_S_C_ * SE3d::exp(Vector6d(velocity_ * (t - last_t_)));
}

void FrameTracker::updateMotion(double t, const SE3d& T_S_C) {
  if (have_motion_ && t > last_t_) {
    velocity_ = (last_T_S_C_.inverse() * T_S_C).log() / (t - last_t_);
  }
  have_motion_ = true;
  last_t_ = t;
  last_T_S_C_ = T_S_C;
}

std::vector<FrameTracker::Track> FrameTracker::detectNewTracks(const cv::Mat& gray, int keyframe_id,
                                                               int* count) {
  std::vector<cv::Point2f> existing;
  existing.reserve(tracks_.size());
  for (const auto& track : tracks_) existing.push_back(track.pixel);
  const std::vector<cv::Point2f> corners = detector_.detect(gray, existing);
  std::vector<Track> fresh;
  for (const auto& corner : corners) {
    Track track;
    if (!undistort(corner, track.normalized)) continue;
    track.id = next_track_id_++;
    track.pixel = corner;
    if (keyframe_id >= 0) track.sightings.push_back({keyframe_id, toEigen(corner), track.normalized});
    fresh.push_back(std::move(track));
  }
  *count = int(fresh.size());
  return fresh;
}

void FrameTracker::finish() {
  if (state_ != State::initialising || !have_reference_) return;
  const std::string attempt = "reference frame " + std::to_string(reference_frame_) +
                              ", tried up to frame " + std::to_string(last_frame_index_) + ": " +
                              (last_init_failure_.empty() ? std::string("no attempt") : last_init_failure_);
  init_attempts_.push_back(attempt);
  loss_reasons_.emplace(reference_frame_, "initialisation failed: " + attempt);
}

ImagePyramid FrameTracker::pyramidToTrackInto(const PrefetchedFrame& frame, const ImagePyramid& own,
                                              const std::vector<cv::Point2f>& points,
                                              const std::vector<cv::Point2f>& guesses) {
  if (!options_.compensate_gain || last_linear_.empty() || frame.linear.empty() ||
      last_linear_.size() != frame.linear.size()) {
    return own;
  }
  // Boxes a KLT window wide either side of the point: much larger than the
  // guesses' error, small enough to stay on the seabed the track sees.
  const RelativeGain gain = estimateRelativeGain(last_linear_, frame.linear, last_saturated_, frame.saturated,
                                                 points, guesses, klt_.windowPx());
  const double step_db = std::abs(gain.db());
  if (gain.samples == 0 || step_db < options_.gain_compensation_min_db || step_db < 3.0 * gain.sigma_db) {
    return own;
  }
  ++gain_compensated_frames_;
  largest_gain_step_db_ = std::max(largest_gain_step_db_, step_db);
  return klt_.buildPyramid(equaliser_.equalise(compensateGain(frame.linear, gain.ratio)));
}

// ---------------------------------------------------------------------------
// Initialisation

void FrameTracker::startReference(const PrefetchedFrame& frame, FrameRecord& record,
                                  const ImagePyramid& pyramid, const cv::Mat& gray) {
  Stopwatch watch;
  tracks_.clear();
  int count = 0;
  tracks_ = detectNewTracks(gray, -1, &count);
  record.new_corners = count;
  stepMs(record, FrontendStep::detect) += watch.lapMs();
  buffer_.clear();
  reference_points_.clear();
  if (count < options_.min_corners) {
    have_reference_ = false;
    tracks_.clear();
    record.status = FrameStatus::lost;
    loss_reasons_.emplace(record.index, "no texture: " + std::to_string(count) +
                                            " corners found, fewer than " +
                                            std::to_string(options_.min_corners));
    return;
  }
  have_reference_ = true;
  reference_frame_ = frame.index;
  reference_record_ = records_.size() - 1;
  reference_t_ = frame.t;
  for (const auto& track : tracks_) {
    reference_points_[track.id] = {toEigen(track.pixel), track.normalized};
  }
  last_pyramid_ = pyramid;
  last_linear_ = frame.linear;
  last_saturated_ = frame.saturated;
  record.status = FrameStatus::initialising;
  record.tracked = int(tracks_.size());
}

void FrameTracker::processInitialising(const PrefetchedFrame& frame, FrameRecord& record,
                                       const ImagePyramid& pyramid) {
  if (!have_reference_) {
    startReference(frame, record, pyramid, frame.gray);
    return;
  }
  Stopwatch watch;
  std::vector<cv::Point2f> points, guesses, tracked;
  for (const auto& track : tracks_) {
    points.push_back(track.pixel);
    guesses.push_back(track.pixel + track.velocity);
  }
  const std::vector<bool> good =
      klt_.track(last_pyramid_, pyramidToTrackInto(frame, pyramid, points, guesses), points, guesses, tracked);
  std::vector<Track> survivors;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (!good[i]) continue;
    Track track = tracks_[i];
    if (!undistort(tracked[i], track.normalized)) continue;
    track.velocity = tracked[i] - track.pixel;
    track.pixel = tracked[i];
    survivors.push_back(std::move(track));
  }
  tracks_ = std::move(survivors);
  last_pyramid_ = pyramid;
  last_linear_ = frame.linear;
  last_saturated_ = frame.saturated;
  record.tracked = int(tracks_.size());
  record.status = FrameStatus::initialising;
  stepMs(record, FrontendStep::track) += watch.lapMs();

  BufferedFrame buffered;
  buffered.record = records_.size() - 1;
  for (const auto& track : tracks_) buffered.track_pixels.emplace_back(track.id, track.pixel);
  buffer_.push_back(std::move(buffered));

  const bool too_few = int(tracks_.size()) < options_.init_min_tracks;
  const bool too_old = frame.index - reference_frame_ > options_.init_max_reference_age;
  if (!too_few && tryInitialise(frame, record)) return;
  if (too_few || too_old) {
    std::ostringstream attempt;
    attempt << "reference frame " << reference_frame_ << ", tried up to frame " << frame.index << ": "
            << (too_few ? std::to_string(tracks_.size()) + " tracks left, fewer than " +
                              std::to_string(options_.init_min_tracks)
                        : last_init_failure_.empty() ? std::string("no attempt") : last_init_failure_);
    init_attempts_.push_back(attempt.str());
    // The frames since the reference stay unposed; say why.
    loss_reasons_.emplace(reference_frame_, "initialisation failed: " + attempt.str());
    for (const auto& b : buffer_) {
      loss_reasons_.emplace(records_[b.record].index, "initialisation failed: " + attempt.str());
    }
    records_.back().status = FrameStatus::initialising;
    startReference(frame, records_.back(), pyramid, frame.gray);
  }
}

bool FrameTracker::tryInitialise(const PrefetchedFrame& frame, FrameRecord& record) {
  // Cheap pre-check: the median angle between matched rays (rotation
  // included) must reach the parallax asked for; otherwise wait.
  std::vector<double> angles;
  std::vector<Eigen::Vector2d> n1, n2, p1, p2;
  std::vector<int> ids;
  for (const auto& track : tracks_) {
    const auto it = reference_points_.find(track.id);
    if (it == reference_points_.end()) continue;
    const Eigen::Vector3d a = Eigen::Vector3d(it->second.second.x(), it->second.second.y(), 1.0).normalized();
    const Eigen::Vector3d b = Eigen::Vector3d(track.normalized.x(), track.normalized.y(), 1.0).normalized();
    angles.push_back(std::atan2(a.cross(b).norm(), a.dot(b)));
    n1.push_back(it->second.second);
    n2.push_back(track.normalized);
    p1.push_back(it->second.first);
    p2.push_back(toEigen(track.pixel));
    ids.push_back(track.id);
  }
  if (upperMedian(angles) < options_.init_min_parallax_deg * kDegToRad) {
    char text[128];
    std::snprintf(text, sizeof(text), "median ray angle %.2f deg, below the %.2f deg of parallax asked for",
                  upperMedian(angles) / kDegToRad, options_.init_min_parallax_deg);
    last_init_failure_ = text;
    return false;
  }
  Stopwatch watch;
  TwoViewOptions two_view;
  two_view.ransac_threshold_px = options_.ransac_threshold_px * error_scale_;
  two_view.max_error_px = options_.max_triangulation_error_px * error_scale_;
  two_view.min_parallax_rad = options_.init_min_parallax_deg * kDegToRad;
  two_view.min_landmarks = options_.init_min_landmarks;
  two_view.min_cheirality_fraction = options_.init_min_cheirality_fraction;
  const TwoViewResult start = initializeTwoView(n1, n2, p1, p2, camera_, two_view);
  stepMs(record, FrontendStep::triangulate) += watch.lapMs();
  if (!start.ok) {
    last_init_failure_ = start.failure;
    return false;
  }

  // A new segment: the reference frame's camera is its frame S.
  segment_ = int(segments_.size());
  segments_.push_back({segment_, reference_frame_, frame.index, {}});
  const int kf0 = map_.addKeyframe(reference_frame_, reference_t_, segment_, SE3d());
  const int kf1 = map_.addKeyframe(frame.index, frame.t, segment_, start.T_C1_C2);
  segments_.back().keyframe_ids = {kf0, kf1};
  // The two keyframes' poses rest on the landmarks of the start: those are
  // their frame observations (the reference frame's now, this frame's after
  // the buffered frames between them, to keep the list in frame order).
  std::map<int, int> track_landmarks;
  std::vector<FrameObservation> current_observations;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (!start.p_C1[i]) continue;
    const int l = map_.addLandmark(segment_, *start.p_C1[i]);
    map_.addObservation(kf0, l, p1[i]);
    map_.addObservation(kf1, l, p2[i]);
    track_landmarks[ids[i]] = l;
    frame_observations_.push_back({reference_frame_, l, float(p1[i].x()), float(p1[i].y())});
    current_observations.push_back({frame.index, l, float(p2[i].x()), float(p2[i].y())});
  }
  for (auto& track : tracks_) {
    const auto it = track_landmarks.find(track.id);
    if (it != track_landmarks.end()) {
      track.landmark = it->second;
      continue;
    }
    const auto ref = reference_points_.find(track.id);
    if (ref != reference_points_.end()) {
      track.sightings.push_back({kf0, ref->second.first, ref->second.second});
    }
    track.sightings.push_back({kf1, toEigen(track.pixel), track.normalized});
  }
  // The reference frame and this one are keyframes, posed.
  FrameRecord& reference = records_[reference_record_];
  reference.posed = true;
  reference.T_F_C = SE3d();
  reference.keyframe = true;
  reference.keyframe_id = kf0;
  reference.segment = segment_;
  reference.inliers = start.landmarks;
  anchors_[reference_record_] = {kf0, SE3d()};
  record.posed = true;
  record.T_F_C = start.T_C1_C2;
  record.keyframe = true;
  record.keyframe_id = kf1;
  record.segment = segment_;
  record.inliers = start.landmarks;
  record.status = FrameStatus::tracking;
  anchors_.back() = {kf1, SE3d()};
  poseBufferedFrames(track_landmarks);
  frame_observations_.insert(frame_observations_.end(), current_observations.begin(),
                             current_observations.end());

  state_ = State::tracking;
  failed_frames_ = 0;
  have_motion_ = false;
  last_t_ = reference_t_;
  last_T_S_C_ = SE3d();
  updateMotion(frame.t, start.T_C1_C2);
  last_keyframe_ = kf1;
  frames_since_keyframe_ = 0;
  keyframes_since_ba_ = 0;
  last_keyframe_landmarks_.clear();
  std::vector<cv::Point2f> landmark_pixels;
  for (const auto& o : map_.keyframe(kf1).observations) {
    last_keyframe_landmarks_.insert(o.landmark_id);
    landmark_pixels.emplace_back(float(o.pixel.x()), float(o.pixel.y()));
  }
  coverage_at_last_keyframe_ = detector_.coverage(landmark_pixels);
  // Fill the grid at the new keyframe.
  watch.lapMs();
  int count = 0;
  std::vector<Track> fresh = detectNewTracks(frame.gray, kf1, &count);
  for (auto& track : fresh) tracks_.push_back(std::move(track));
  record.new_corners += count;
  record.tracked = int(tracks_.size());
  stepMs(record, FrontendStep::detect) += watch.lapMs();
  buffer_.clear();
  reference_points_.clear();
  have_reference_ = false;
  return true;
}

void FrameTracker::poseBufferedFrames(const std::map<int, int>& track_landmarks) {
  const SE3d T_S_C1 = map_.keyframe(segments_.back().keyframe_ids[1]).T_F_C;
  const double t1 = map_.keyframe(segments_.back().keyframe_ids[1]).t;
  const int kf0 = segments_.back().keyframe_ids[0];
  for (const auto& buffered : buffer_) {
    FrameRecord& record = records_[buffered.record];
    if (record.posed) continue;  // the current frame
    std::vector<PoseCorrespondence> correspondences;
    std::vector<int> correspondence_landmark;
    for (const auto& [track_id, pixel] : buffered.track_pixels) {
      const auto it = track_landmarks.find(track_id);
      if (it == track_landmarks.end()) continue;
      PoseCorrespondence c;
      if (!undistort(pixel, c.normalized)) continue;
      c.p_F = map_.landmark(it->second).p_F;
      c.pixel = toEigen(pixel);
      correspondences.push_back(c);
      correspondence_landmark.push_back(it->second);
    }
    const double alpha = t1 > reference_t_ ? (record.t - reference_t_) / (t1 - reference_t_) : 0.0;
    const SE3d prediction = SE3d::interpolate(SE3d(), T_S_C1, alpha);
    const PoseEstimate estimate = estimateFramePose(correspondences, prediction, camera_, pose_options_);
    if (!estimate.ok) {
      loss_reasons_.emplace(record.index, "initialisation: " + estimate.failure);
      continue;
    }
    record.posed = true;
    record.T_F_C = estimate.T_F_C;
    record.inliers = estimate.inlier_count;
    record.segment = segment_;
    record.status = FrameStatus::initialising;
    anchors_[buffered.record] = {kf0, estimate.T_F_C};  // KF0 is the identity of S
    const std::size_t first = frame_observations_.size();
    for (std::size_t j = 0; j < correspondences.size(); ++j) {
      if (!estimate.inliers[j]) continue;
      const Eigen::Vector2d& pixel = correspondences[j].pixel;  // a float, from KLT
      frame_observations_.push_back({record.index, correspondence_landmark[j], float(pixel.x()), float(pixel.y())});
    }
    sortFrameObservationsFrom(first);
  }
}

// ---------------------------------------------------------------------------
// Tracking

void FrameTracker::processTracking(const PrefetchedFrame& frame, FrameRecord& record,
                                   const ImagePyramid& pyramid) {
  Stopwatch watch;
  const SE3d prediction = predictPose(frame.t);
  const SE3d T_C_S_predicted = prediction.inverse();
  std::vector<cv::Point2f> points, guesses, tracked;
  points.reserve(tracks_.size());
  guesses.reserve(tracks_.size());
  // Landmark tracks start where the predicted pose projects them; the others
  // move by the median of that predicted image motion (or their own last
  // motion when no landmark is in view).
  std::vector<double> dx, dy;
  for (const auto& track : tracks_) {
    cv::Point2f guess = track.pixel + track.velocity * float(failed_frames_ + 1);
    if (track.landmark >= 0 && map_.landmark(track.landmark).valid) {
      const Eigen::Vector3d p_C = T_C_S_predicted * map_.landmark(track.landmark).p_F;
      if (p_C.z() > 0.0) {
        const Eigen::Vector2d uv = camera_.project(p_C);
        if (camera_.isInImage(uv)) {
          guess = cv::Point2f(float(uv.x()), float(uv.y()));
          dx.push_back(uv.x() - track.pixel.x);
          dy.push_back(uv.y() - track.pixel.y);
        }
      }
    }
    points.push_back(track.pixel);
    guesses.push_back(guess);
  }
  if (dx.size() >= 10) {
    const cv::Point2f shift(float(upperMedian(dx)), float(upperMedian(dy)));
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
      if (tracks_[i].landmark < 0) guesses[i] = tracks_[i].pixel + shift;
    }
  }
  const std::vector<bool> good =
      klt_.track(last_pyramid_, pyramidToTrackInto(frame, pyramid, points, guesses), points, guesses, tracked);
  std::vector<Track> candidates;
  candidates.reserve(tracks_.size());
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (!good[i]) continue;
    Track track = tracks_[i];
    if (!undistort(tracked[i], track.normalized)) continue;
    track.velocity = (tracked[i] - track.pixel) * (1.0f / float(failed_frames_ + 1));
    track.pixel = tracked[i];
    if (track.landmark >= 0 && !map_.landmark(track.landmark).valid) track.landmark = -1;
    candidates.push_back(std::move(track));
  }
  record.tracked = int(candidates.size());
  stepMs(record, FrontendStep::track) += watch.lapMs();
  if (int(candidates.size()) < options_.min_tracked_points) {
    markLost(record, FrameStatus::lost,
             "too few tracked points (" + std::to_string(candidates.size()) + ", fewer than " +
                 std::to_string(options_.min_tracked_points) + ")");
    return;
  }

  std::vector<PoseCorrespondence> correspondences;
  std::vector<std::size_t> correspondence_track;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].landmark < 0) continue;
    correspondences.push_back({map_.landmark(candidates[i].landmark).p_F, candidates[i].normalized,
                               toEigen(candidates[i].pixel)});
    correspondence_track.push_back(i);
  }
  const PoseEstimate estimate = estimateFramePose(correspondences, prediction, camera_, pose_options_);
  stepMs(record, FrontendStep::pnp) += watch.lapMs();
  if (!estimate.ok) {
    markLost(record, FrameStatus::lost, "pose failed: " + estimate.failure);
    return;
  }
  // Commit: outlier tracks of landmarks are dropped (KLT slid off the corner);
  // the inliers are the frame's observations.
  std::vector<bool> keep(candidates.size(), true);
  const std::size_t first_observation = frame_observations_.size();
  for (std::size_t j = 0; j < correspondences.size(); ++j) {
    const Track& track = candidates[correspondence_track[j]];
    if (estimate.inliers[j]) {
      frame_observations_.push_back({frame.index, track.landmark, track.pixel.x, track.pixel.y});
    } else {
      keep[correspondence_track[j]] = false;
    }
  }
  sortFrameObservationsFrom(first_observation);
  tracks_.clear();
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (keep[i]) tracks_.push_back(std::move(candidates[i]));
  }
  last_pyramid_ = pyramid;
  last_linear_ = frame.linear;
  last_saturated_ = frame.saturated;
  failed_frames_ = 0;
  record.posed = true;
  record.T_F_C = estimate.T_F_C;
  record.inliers = estimate.inlier_count;
  record.segment = segment_;
  record.status = FrameStatus::tracking;
  record.tracked = int(tracks_.size());
  ++frames_since_keyframe_;
  segments_.back().last_frame = frame.index;
  const SE3d T_S_K = map_.keyframe(last_keyframe_).T_F_C;  // a copy: makeKeyframe grows the map
  anchors_.back() = {last_keyframe_, T_S_K.inverse() * estimate.T_F_C};

  // Keyframe decision.
  KeyframeInputs inputs;
  std::vector<double> parallax;
  std::vector<cv::Point2f> landmark_pixels;
  const Eigen::Vector3d c_K = T_S_K.t;
  const Eigen::Vector3d c_C = estimate.T_F_C.t;
  for (const auto& track : tracks_) {
    if (track.landmark < 0) continue;
    ++inputs.tracked_landmarks;
    landmark_pixels.push_back(track.pixel);
    if (last_keyframe_landmarks_.count(track.landmark)) ++inputs.tracked_from_last_keyframe;
    const Eigen::Vector3d& p = map_.landmark(track.landmark).p_F;
    const Eigen::Vector3d a = (p - c_K).normalized(), b = (p - c_C).normalized();
    parallax.push_back(std::atan2(a.cross(b).norm(), a.dot(b)));
  }
  inputs.median_parallax_deg = upperMedian(parallax) / kDegToRad;
  inputs.landmarks_at_last_keyframe = int(last_keyframe_landmarks_.size());
  inputs.coverage = detector_.coverage(landmark_pixels);
  inputs.coverage_at_last_keyframe = coverage_at_last_keyframe_;
  inputs.frames_since_keyframe = frames_since_keyframe_;
  KeyframePolicyOptions policy;
  policy.parallax_deg = options_.keyframe_parallax_deg;
  policy.min_tracked_fraction = options_.keyframe_min_tracked_fraction;
  policy.min_coverage = options_.keyframe_min_coverage;
  policy.min_interval = options_.keyframe_min_interval;
  if (decideKeyframe(inputs, policy) != KeyframeReason::none) {
    makeKeyframe(frame, record, frame.gray);
  }
  updateMotion(frame.t, record.T_F_C);
}

void FrameTracker::makeKeyframe(const PrefetchedFrame& frame, FrameRecord& record, const cv::Mat& gray) {
  Stopwatch watch;
  const int kf = map_.addKeyframe(frame.index, frame.t, segment_, record.T_F_C);
  segments_.back().keyframe_ids.push_back(kf);
  record.keyframe = true;
  record.keyframe_id = kf;
  anchors_.back() = {kf, SE3d()};
  for (const auto& track : tracks_) {
    if (track.landmark >= 0) map_.addObservation(kf, track.landmark, toEigen(track.pixel));
  }

  // New landmarks from tracks seen at earlier keyframes.
  TriangulationLimits limits;
  limits.min_angle_rad = options_.min_triangulation_angle_deg * kDegToRad;
  limits.max_error_px = options_.max_triangulation_error_px * error_scale_;
  std::vector<Track> kept;
  kept.reserve(tracks_.size());
  for (auto& track : tracks_) {
    if (track.landmark >= 0 || track.sightings.empty()) {
      kept.push_back(std::move(track));
      continue;
    }
    std::vector<TriangulationView> views;
    for (const auto& s : track.sightings) {
      views.push_back({map_.keyframe(s.keyframe_id).T_F_C, s.normalized, s.pixel});
    }
    views.push_back({record.T_F_C, track.normalized, toEigen(track.pixel)});
    const TriangulationResult result = triangulateLandmark(views, camera_, limits);
    if (result.ok()) {
      const int l = map_.addLandmark(segment_, result.p_F);
      for (const auto& s : track.sightings) map_.addObservation(s.keyframe_id, l, s.pixel);
      map_.addObservation(kf, l, toEigen(track.pixel));
      track.landmark = l;
      track.sightings.clear();
      kept.push_back(std::move(track));
    } else if (result.outcome == TriangulationOutcome::low_parallax) {
      track.sightings.push_back({kf, toEigen(track.pixel), track.normalized});
      kept.push_back(std::move(track));
    }
    // Behind a camera or inconsistent across views: a bad track, dropped.
  }
  tracks_ = std::move(kept);
  stepMs(record, FrontendStep::triangulate) += watch.lapMs();

  int count = 0;
  std::vector<Track> fresh = detectNewTracks(gray, kf, &count);
  for (auto& track : fresh) tracks_.push_back(std::move(track));
  record.new_corners += count;
  record.tracked = int(tracks_.size());
  stepMs(record, FrontendStep::detect) += watch.lapMs();

  if (++keyframes_since_ba_ >= options_.ba_every_keyframes) {
    keyframes_since_ba_ = 0;
    const std::vector<int>& ids = segments_.back().keyframe_ids;
    const std::size_t n = std::min<std::size_t>(ids.size(), std::size_t(options_.ba_window_keyframes));
    const std::vector<int> window(ids.end() - std::ptrdiff_t(n), ids.end());
    adjustLocalWindow(map_, window, camera_, ba_options_);
    // Tracks whose landmark the adjustment removed go on as plain tracks.
    for (auto& track : tracks_) {
      if (track.landmark >= 0 && !map_.landmark(track.landmark).valid) track.landmark = -1;
    }
    record.T_F_C = map_.keyframe(kf).T_F_C;
    stepMs(record, FrontendStep::ba) += watch.lapMs();
  }

  last_keyframe_ = kf;
  frames_since_keyframe_ = 0;
  last_keyframe_landmarks_.clear();
  std::vector<cv::Point2f> landmark_pixels;
  for (const auto& o : map_.keyframe(kf).observations) {
    last_keyframe_landmarks_.insert(o.landmark_id);
    landmark_pixels.emplace_back(float(o.pixel.x()), float(o.pixel.y()));
  }
  coverage_at_last_keyframe_ = detector_.coverage(landmark_pixels);
}

}  // namespace hsmap
