#pragma once
// FrameTracker: the per-frame state machine of the front-end. It owns the
// KLT tracks, the map being built and the motion model, and turns each
// pre-processed frame into a FrameRecord:
//
//   initialising  no map yet (start, or after a loss): a reference frame's
//                 corners are tracked until the two-view start succeeds
//                 (two_view_initializer.h); it is retried on every later
//                 frame, and the reference is renewed when it gets too old
//                 or loses its tracks. On success the reference and the
//                 current frame become the segment's first two keyframes and
//                 the frames in between are posed by PnP on the new landmarks.
//   tracking      tracks are predicted (landmarks projected with the motion
//                 model's pose), tracked by KLT with the forward-backward
//                 check, the frame is posed (frame_pose_estimator.h), and the
//                 keyframe policy decides whether it becomes a keyframe: then
//                 landmarks are triangulated from tracks seen at earlier
//                 keyframes, new corners fill the empty grid cells, and the
//                 local window is bundle-adjusted.
//   loss          a frame without texture, undecodable, or that cannot be
//                 posed is not posed. Up to `max_bridged_frames` such frames
//                 are bridged (the next frame is tracked from the last posed
//                 one); beyond that the segment ends and the tracker
//                 re-initialises a new segment in a frame of its own.
//
// Poses are in the frame of the current segment S (its first keyframe's
// camera, median depth 1). A frame that is not a keyframe stores its pose
// relative to the last keyframe (T_K_C), so that when bundle adjustment
// later moves that keyframe the frame moves with it (finish()).
//
// Every posed frame also keeps the correspondences its pose rests on
// (frameObservations(): the final PnP inliers, or the two-view start's
// landmarks for a segment's first two keyframes), in segment landmark ids;
// the runner maps them into the linked map.

#include <map>
#include <memory>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "core/geometry/pinhole_radtan_camera.h"
#include "pipelines/frontend/corner_detector.h"
#include "pipelines/frontend/frame_pose_estimator.h"
#include "pipelines/frontend/frame_prefetcher.h"
#include "pipelines/frontend/frontend_options.h"
#include "pipelines/frontend/frontend_result.h"
#include "pipelines/frontend/image_preprocessor.h"
#include "pipelines/frontend/klt_tracker.h"
#include "pipelines/frontend/local_bundle_adjuster.h"
#include "pipelines/frontend/visual_map.h"

namespace hsmap {

// What the tracker knows about a frame beyond its FrameRecord.
struct FramePoseAnchor {
  int keyframe_id = -1;  // pose = T_S_K(keyframe) * T_K_C; -1: not posed
  SE3d T_K_C;
};

struct SegmentSpan {
  int id = 0;
  int first_frame = -1;
  int last_frame = -1;
  std::vector<int> keyframe_ids;
};

class FrameTracker {
 public:
  FrameTracker(const FrontendOptions& options, const PinholeRadtanCamera& camera);

  // Processes the next frame (in survey order) and appends its record.
  void process(const PrefetchedFrame& frame);
  // After the last frame: an initialisation still pending is recorded as an
  // attempt (initialisationAttempts()) and its frames' reasons are set.
  void finish();

  const VisualMap& map() const { return map_; }
  VisualMap& map() { return map_; }
  const std::vector<FrameRecord>& records() const { return records_; }
  std::vector<FrameRecord>& records() { return records_; }
  const std::vector<FramePoseAnchor>& anchors() const { return anchors_; }
  const std::vector<SegmentSpan>& segments() const { return segments_; }
  // Frame index -> why it was not posed (or why initialisation failed).
  const std::map<int, std::string>& lossReasons() const { return loss_reasons_; }
  // "reference 12, tried 13-40: median parallax ... below ..." per reference frame.
  const std::vector<std::string>& initialisationAttempts() const { return init_attempts_; }
  // Of every frame posed so far, sorted by frame, then landmark (ids of map();
  // some may have been removed from it since).
  const std::vector<FrameObservation>& frameObservations() const { return frame_observations_; }
  // Moves them out (the tracker keeps none), for the runner.
  std::vector<FrameObservation> takeFrameObservations() { return std::exchange(frame_observations_, {}); }
  // Frames brought to the last frame's exposure before tracking (a gain
  // step, exposure_compensation.h), and the largest step among them (dB).
  int gainCompensatedFrames() const { return gain_compensated_frames_; }
  double largestGainStepDb() const { return largest_gain_step_db_; }

 private:
  struct Sighting {
    int keyframe_id;
    Eigen::Vector2d pixel;
    Eigen::Vector2d normalized;
  };
  struct Track {
    int id = 0;
    cv::Point2f pixel;
    cv::Point2f velocity{0.0f, 0.0f};  // last frame-to-frame displacement
    Eigen::Vector2d normalized = Eigen::Vector2d::Zero();
    int landmark = -1;
    std::vector<Sighting> sightings;  // keyframes that saw it before it became a landmark
  };
  struct BufferedFrame {
    std::size_t record;  // index into records_
    std::vector<std::pair<int, cv::Point2f>> track_pixels;  // track id -> pixel
  };

  void processInitialising(const PrefetchedFrame& frame, FrameRecord& record, const ImagePyramid& pyramid);
  void processTracking(const PrefetchedFrame& frame, FrameRecord& record, const ImagePyramid& pyramid);
  void startReference(const PrefetchedFrame& frame, FrameRecord& record, const ImagePyramid& pyramid,
                      const cv::Mat& gray);
  bool tryInitialise(const PrefetchedFrame& frame, FrameRecord& record);
  void poseBufferedFrames(const std::map<int, int>& track_landmarks);
  void makeKeyframe(const PrefetchedFrame& frame, FrameRecord& record, const cv::Mat& gray);
  void markLost(FrameRecord& record, FrameStatus status, const std::string& reason);
  // Sorts the observations appended since `first` (one frame's) by landmark.
  void sortFrameObservationsFrom(std::size_t first);
  // The current segment ends (its frames keep their poses); re-initialise.
  void endSegment();
  SE3d predictPose(double t) const;
  void updateMotion(double t, const SE3d& T_S_C);
  std::vector<Track> detectNewTracks(const cv::Mat& gray, int keyframe_id, int* count);
  bool undistort(const cv::Point2f& pixel, Eigen::Vector2d& normalized) const;
  // The pyramid KLT tracks into from last_pyramid_: the frame's own, or,
  // when the frame's exposure differs from the last tracked frame's (a gain
  // step measured at the tracks, exposure_compensation.h), the frame brought
  // to that exposure.
  ImagePyramid pyramidToTrackInto(const PrefetchedFrame& frame, const ImagePyramid& own,
                                  const std::vector<cv::Point2f>& points,
                                  const std::vector<cv::Point2f>& guesses);

  FrontendOptions options_;
  PinholeRadtanCamera camera_;
  KltTracker klt_;
  GridCornerDetector detector_;
  PoseEstimatorOptions pose_options_;
  LocalBundleAdjustmentOptions ba_options_;
  double error_scale_;

  VisualMap map_;
  std::vector<FrameRecord> records_;
  std::vector<FramePoseAnchor> anchors_;
  std::vector<SegmentSpan> segments_;
  std::map<int, std::string> loss_reasons_;
  std::vector<std::string> init_attempts_;
  std::vector<FrameObservation> frame_observations_;

  enum class State { initialising, tracking } state_ = State::initialising;
  std::vector<Track> tracks_;
  int next_track_id_ = 0;
  ImagePyramid last_pyramid_;   // of the last frame tracked into (posed, or the init reference chain)
  cv::Mat last_linear_;         // its image before CLAHE (compensate_gain only)
  cv::Mat last_saturated_;      // and its saturated pixels
  ImagePreprocessor equaliser_; // CLAHE of a gain-compensated frame
  int gain_compensated_frames_ = 0;
  double largest_gain_step_db_ = 0.0;
  int failed_frames_ = 0;       // consecutive frames not posed while tracking

  // Initialisation.
  bool have_reference_ = false;
  int reference_frame_ = -1;
  std::size_t reference_record_ = 0;
  double reference_t_ = 0.0;
  std::map<int, std::pair<Eigen::Vector2d, Eigen::Vector2d>> reference_points_;  // track -> (pixel, normalized)
  std::vector<BufferedFrame> buffer_;
  std::string last_init_failure_;
  int last_frame_index_ = -1;

  // Tracking.
  int segment_ = -1;
  int last_keyframe_ = -1;
  int frames_since_keyframe_ = 0;
  int keyframes_since_ba_ = 0;
  std::unordered_set<int> last_keyframe_landmarks_;
  double coverage_at_last_keyframe_ = 1.0;
  bool have_motion_ = false;
  double last_t_ = 0.0;
  SE3d last_T_S_C_;
  Vector6d velocity_ = Vector6d::Zero();  // body twist per second, right-perturbation
};

}  // namespace hsmap
