#pragma once
// VisualMap: the sparse map of the front-end — keyframes with their poses
// T_F_C and their 2D observations, and landmarks p_F with the keyframes that
// see them. F is the front-end's frame: that of the first map segment, up to
// scale (docs/FRONTEND.md); a later segment lives in its own frame until the
// segment linker moves it into F.
//
// Ids are dense and stable: keyframe k is keyframes()[k], landmark l is
// landmarks()[l]. A removed landmark keeps its slot with valid == false (and
// no observations), so ids held elsewhere (tracks, outputs) never dangle.
// Every observation is stored twice, in its keyframe (pixel) and in its
// landmark (keyframe id), and the two stay in step through the methods here.
//
// Pixels are as measured: distorted, in the survey image, pixel centres at
// integer coordinates (docs/SURVEY_FORMAT.md).

#include <Eigen/Core>
#include <vector>

#include "core/geometry/se3.h"

namespace hsmap {

struct KeyframeObservation {
  int landmark_id = -1;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
};

struct Keyframe {
  int id = -1;
  int frame_index = -1;  // the survey frame it was taken from
  double t = 0.0;
  int segment = 0;
  SE3d T_F_C;
  std::vector<KeyframeObservation> observations;
};

struct Landmark {
  int id = -1;
  int segment = 0;
  Eigen::Vector3d p_F = Eigen::Vector3d::Zero();
  std::vector<int> keyframe_ids;  // keyframes that observe it (each once)
  bool valid = true;
};

class VisualMap {
 public:
  int addKeyframe(int frame_index, double t, int segment, const SE3d& T_F_C);
  int addLandmark(int segment, const Eigen::Vector3d& p_F);
  // Adds the observation to both sides. A landmark seen twice by one
  // keyframe keeps the first pixel (returns false).
  bool addObservation(int keyframe_id, int landmark_id, const Eigen::Vector2d& pixel);
  void removeObservation(int keyframe_id, int landmark_id);
  // Removes the landmark and all its observations (valid = false).
  void removeLandmark(int landmark_id);

  const std::vector<Keyframe>& keyframes() const { return keyframes_; }
  const std::vector<Landmark>& landmarks() const { return landmarks_; }
  Keyframe& keyframe(int id) { return keyframes_.at(std::size_t(id)); }
  const Keyframe& keyframe(int id) const { return keyframes_.at(std::size_t(id)); }
  Landmark& landmark(int id) { return landmarks_.at(std::size_t(id)); }
  const Landmark& landmark(int id) const { return landmarks_.at(std::size_t(id)); }

  std::size_t validLandmarkCount() const;
  std::size_t observationCount() const;

  // For the reader: replaces the contents wholesale (ids must be dense).
  void assign(std::vector<Keyframe> keyframes, std::vector<Landmark> landmarks);

 private:
  std::vector<Keyframe> keyframes_;
  std::vector<Landmark> landmarks_;
};

}  // namespace hsmap
