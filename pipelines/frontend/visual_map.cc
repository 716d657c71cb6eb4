#include "pipelines/frontend/visual_map.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace hsmap {

int VisualMap::addKeyframe(int frame_index, double t, int segment, const SE3d& T_F_C) {
  Keyframe keyframe;
  keyframe.id = static_cast<int>(keyframes_.size());
  keyframe.frame_index = frame_index;
  keyframe.t = t;
  keyframe.segment = segment;
  keyframe.T_F_C = T_F_C;
  keyframes_.push_back(std::move(keyframe));
  return keyframes_.back().id;
}

int VisualMap::addLandmark(int segment, const Eigen::Vector3d& p_F) {
  Landmark landmark;
  landmark.id = static_cast<int>(landmarks_.size());
  landmark.segment = segment;
  landmark.p_F = p_F;
  landmarks_.push_back(std::move(landmark));
  return landmarks_.back().id;
}

bool VisualMap::addObservation(int keyframe_id, int landmark_id, const Eigen::Vector2d& pixel) {
  Keyframe& kf = keyframe(keyframe_id);
  Landmark& lm = landmark(landmark_id);
  if (!lm.valid) {
    throw std::logic_error("VisualMap: observation of removed landmark " + std::to_string(landmark_id));
  }
  if (std::find(lm.keyframe_ids.begin(), lm.keyframe_ids.end(), keyframe_id) !=
      lm.keyframe_ids.end()) {
    return false;
  }
  kf.observations.push_back({landmark_id, pixel});
  lm.keyframe_ids.push_back(keyframe_id);
  return true;
}

void VisualMap::removeObservation(int keyframe_id, int landmark_id) {
  Keyframe& kf = keyframe(keyframe_id);
  Landmark& lm = landmark(landmark_id);
  auto& obs = kf.observations;
  obs.erase(std::remove_if(obs.begin(), obs.end(),
                           [&](const KeyframeObservation& o) { return o.landmark_id == landmark_id; }),
            obs.end());
  auto& ids = lm.keyframe_ids;
  ids.erase(std::remove(ids.begin(), ids.end(), keyframe_id), ids.end());
}

void VisualMap::removeLandmark(int landmark_id) {
  Landmark& lm = landmark(landmark_id);
  const std::vector<int> observers = lm.keyframe_ids;
  for (int kf : observers) removeObservation(kf, landmark_id);
  lm.valid = false;
}

std::size_t VisualMap::validLandmarkCount() const {
  return std::size_t(std::count_if(landmarks_.begin(), landmarks_.end(),
                                   [](const Landmark& l) { return l.valid; }));
}

std::size_t VisualMap::observationCount() const {
  std::size_t n = 0;
  for (const auto& kf : keyframes_) n += kf.observations.size();
  return n;
}

void VisualMap::assign(std::vector<Keyframe> keyframes, std::vector<Landmark> landmarks) {
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    if (keyframes[i].id != int(i)) throw std::invalid_argument("VisualMap::assign: keyframe ids must be dense");
  }
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    if (landmarks[i].id != int(i)) throw std::invalid_argument("VisualMap::assign: landmark ids must be dense");
  }
  keyframes_ = std::move(keyframes);
  landmarks_ = std::move(landmarks);
}

}  // namespace hsmap
