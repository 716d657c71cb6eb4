#include "pipelines/surface/sparse_map_points.h"

namespace hsmap {

VisibilityPoints visibilityFromSparseMap(const VisualMap& map_W) {
  VisibilityPoints points;
  points.c_W.reserve(map_W.keyframes().size());
  for (const Keyframe& keyframe : map_W.keyframes()) points.c_W.push_back(keyframe.T_F_C.t);
  for (const Landmark& landmark : map_W.landmarks()) {
    if (!landmark.valid || landmark.keyframe_ids.size() < 2) continue;
    points.p_W.push_back(landmark.p_F);
    points.views.push_back(landmark.keyframe_ids);
  }
  return points;
}

}  // namespace hsmap
