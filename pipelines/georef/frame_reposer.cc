#include "pipelines/georef/frame_reposer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <span>
#include <atomic>
#include <cmath>
#include <mutex>

namespace hsmap {

std::vector<Repose> reposeFrames(const std::vector<FrameToRepose>& frames,
                                 const FrontendResult& frontend,
                                 const VisualMap& map, const PinholeRadtanCamera& camera,
                                 const PoseEstimatorOptions& options,
                                 const std::function<void(int)>& progress) {
  PoseEstimatorOptions single = options;
  single.solver_threads = 1;
  std::vector<Repose> results(frames.size());
  std::atomic<int> done{0};
  std::mutex progress_mutex;  // the callback need not be thread-safe
  auto poseOne = [&](std::size_t i) {
    const std::span<const FrameObservation> observed = frontend.observationsOfFrame(frames[i].frame);
    std::vector<PoseCorrespondence> correspondences;
    correspondences.reserve(observed.size());
    for (auto it = observed.begin(); it != observed.end(); ++it) {
      if (it->landmark < 0 || std::size_t(it->landmark) >= map.landmarks().size()) continue;
      const Landmark& landmark = map.landmark(it->landmark);
      if (!landmark.valid) continue;
      const Eigen::Vector2d pixel(it->u, it->v);
      const auto ray = camera.unproject(pixel);
      if (!ray) continue;
      PoseCorrespondence c;
      c.p_F = landmark.p_F;
      c.normalized = ray->head<2>() / ray->z();
      c.pixel = pixel;
      correspondences.push_back(c);
    }
    Repose& result = results[i];
    result.T_W_C = frames[i].prediction;
    if (int(correspondences.size()) >= single.min_inliers) {
      const PoseEstimate estimate =
          estimateFramePose(correspondences, frames[i].prediction, camera, single);
      if (estimate.ok) {
        result.ok = true;
        result.T_W_C = estimate.T_F_C;
        result.inliers = estimate.inlier_count;
        result.rms_px = estimate.rms_error_px;
      }
    }
    const int finished = ++done;
    if (progress && finished % 64 == 0) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress(finished);
    }
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, frames.size(), 16),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) poseOne(i);
                    });
  if (progress) progress(done.load());
  return results;
}

}  // namespace hsmap
