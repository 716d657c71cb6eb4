#include "pipelines/evaluate/view_distance.h"

#include <string>

#include "core/util/median.h"

namespace hsmap {

ViewDistance medianViewDistance(const std::vector<TimedPose>& frames_true,
                                const MeshRayCaster& true_scene) {
  std::vector<Ray> rays(frames_true.size());
  for (std::size_t i = 0; i < frames_true.size(); ++i) {
    rays[i].origin = frames_true[i].T.t;
    rays[i].direction = frames_true[i].T.q * Eigen::Vector3d::UnitZ();  // the optical axis in W
  }
  std::vector<RayHit> hits(rays.size());
  true_scene.intersect(rays, hits);
  ViewDistance out;
  std::vector<double> distances;
  for (const RayHit& hit : hits) {
    if (hit.hit()) {
      distances.push_back(hit.distance);
    } else {
      ++out.frames_missed;
    }
  }
  out.frames_hit = static_cast<int>(distances.size());
  out.h_m = distances.empty()
                ? MetricValue::missing("no true frame's optical axis meets truth/scene.ply (" +
                                       std::to_string(frames_true.size()) +
                                       " frames): no view distance for the view alignment")
                : MetricValue::of(median(distances));
  return out;
}

}  // namespace hsmap
