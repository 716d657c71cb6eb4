#include "pipelines/georef/ins_alignment.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/geometry/rotation_anchored_alignment.h"
#include "pipelines/georef/ins_similarity.h"

namespace hsmap {
namespace {

// Marks the pairs within the threshold of S and returns their RMS.
double classify(const Sim3& S, const std::vector<Eigen::Vector3d>& source,
                const std::vector<Eigen::Vector3d>& target, double threshold,
                std::vector<bool>& inliers, std::vector<double>& residuals, int& count) {
  inliers.assign(source.size(), false);
  residuals.assign(source.size(), 0.0);
  count = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const double error = (target[i] - S.apply(source[i])).norm();
    residuals[i] = error;
    if (error <= threshold) {
      inliers[i] = true;
      ++count;
      sum += error * error;
    }
  }
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}

template <class T>
std::vector<T> selected(const std::vector<T>& values, const std::vector<bool>& keep) {
  std::vector<T> out;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (keep[i]) out.push_back(values[i]);
  }
  return out;
}

}  // namespace

InsAlignment alignVisionToIns(const CameraTrajectory& vision_F, const InsBodyTrack& ins,
                              const SE3d& T_B_C, const InsNoise& noise) {
  InsAlignment result;
  result.threshold_m = std::max(1.0, 4.0 * noise.sigma_horizontal_m);
  std::vector<SE3d> T_F_C;
  for (std::size_t i = 0; i < ins.fixes().size(); ++i) {
    if (!vision_F.visionCovers(ins.fixes()[i].t)) continue;
    result.paired_fixes.push_back(int(i));
    T_F_C.push_back(vision_F.at(ins.fixes()[i].t).T_W_C);
  }
  if (result.paired_fixes.size() < 3) {
    std::ostringstream message;
    message << "cannot geo-reference: only " << result.paired_fixes.size()
            << " INS fixes fall within the time span that vision posed (need at least 3)";
    throw std::runtime_error(message.str());
  }
  std::vector<Eigen::Vector3d> p_F_C;
  for (const SE3d& T : T_F_C) p_F_C.push_back(T.t);

  // INS camera positions: the lever arm turned by R_W_B (measured, or the
  // level, along-track attitude when the INS has none).
  std::vector<Eigen::Vector3d> p_W_C;
  for (int fix_index : result.paired_fixes) {
    const InsBodyFix& fix = ins.fixes()[std::size_t(fix_index)];
    p_W_C.push_back(fix.p_W_B + fix.q_W_B * T_B_C.t);
  }
  RobustAlignment robust;
  try {
    robust = alignUmeyamaRobust(p_F_C, p_W_C, result.threshold_m);
  } catch (const std::exception& error) {
    std::ostringstream message;
    message << "cannot geo-reference: no similarity brings the " << p_F_C.size()
            << " vision camera positions onto the INS fixes (" << error.what() << ")";
    throw std::runtime_error(message.str());
  }
  result.inliers = robust.inliers;
  // Rotation from the attitudes of the inlier fixes, scale and translation
  // from their positions; then the pairs are classified again.
  std::vector<Eigen::Quaterniond> q_W_F;
  for (std::size_t k = 0; k < result.paired_fixes.size(); ++k) {
    if (!result.inliers[k]) continue;
    const InsBodyFix& fix = ins.fixes()[std::size_t(result.paired_fixes[k])];
    q_W_F.push_back(fix.q_W_B * T_B_C.q * T_F_C[k].q.conjugate());
  }
  const Sim3 start = alignScaleTranslation(chordalMeanRotation(q_W_F),
                                           selected(p_F_C, result.inliers),
                                           selected(p_W_C, result.inliers));
  std::vector<CameraAtFix> cameras;
  for (std::size_t k = 0; k < result.paired_fixes.size(); ++k) {
    if (result.inliers[k]) cameras.push_back({result.paired_fixes[k], T_F_C[k]});
  }
  try {
    result.fit = fitMapToIns(cameras, ins, T_B_C, noise, start);
  } catch (const std::invalid_argument& error) {
    throw std::runtime_error(std::string("cannot geo-reference: ") + error.what());
  }
  const Sim3& S = result.fit.S_target_source;
  result.rotation_from = ins.hasAttitude() ? "INS attitude" : "level, along-track attitude (no INS attitude)";
  result.S_W_F = S;
  result.rms_m = classify(S, p_F_C, p_W_C, result.threshold_m, result.inliers, result.residuals_m,
                         result.inlier_count);
  if (result.inlier_count < 3) {
    throw std::runtime_error("cannot geo-reference: fewer than 3 INS fixes agree with vision");
  }
  return result;
}

}  // namespace hsmap
