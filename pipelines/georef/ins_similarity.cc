#include "pipelines/georef/ins_similarity.h"

#include <cmath>

namespace hsmap {

SimilarityFit fitMapToIns(const std::vector<CameraAtFix>& cameras, const InsBodyTrack& ins,
                          const SE3d& T_B_C, const InsNoise& noise, const Sim3& start,
                          InsParts parts) {
  const SE3d T_C_B = T_B_C.inverse();
  const Eigen::Vector3d sigma_position(
      noise.sigma_horizontal_m, noise.sigma_horizontal_m,
      parts == InsParts::without_depth ? noise.sigma_horizontal_m : noise.sigma_depth_m);
  const bool measured_attitude = ins.hasAttitude() && parts != InsParts::without_attitude;
  // Assumed attitudes count once for the survey, and ten times weaker than
  // the adjustment's prior (see the header).
  const double once = kAssumedAttitudeWeakening *
                      std::sqrt(double(std::max<std::size_t>(cameras.size(), 1)));
  const Eigen::Vector3d sigma_attitude =
      measured_attitude ? noise.sigma_attitude_rad
                        : Eigen::Vector3d(noise.assumed_level_sigma_rad * once,
                                          noise.assumed_level_sigma_rad * once,
                                          noise.assumed_heading_sigma_rad * once);
  std::vector<SimilarityFitPosition> positions;
  std::vector<SimilarityFitAttitude> attitudes;
  for (const CameraAtFix& camera : cameras) {
    const InsBodyFix& fix = ins.fixes()[std::size_t(camera.fix)];
    positions.push_back(
        {camera.T_X_C.t, camera.T_X_C.q * T_C_B.t, fix.p_W_B, sigma_position});
    attitudes.push_back({camera.T_X_C.q * T_C_B.q, fix.q_W_B, sigma_attitude});
  }
  return fitSimilarity(positions, attitudes, start);
}

}  // namespace hsmap
