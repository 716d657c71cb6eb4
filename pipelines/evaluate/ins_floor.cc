#include "pipelines/evaluate/ins_floor.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/geometry/pose_interpolation.h"
#include "core/geometry/so3.h"
#include "core/survey/number_text.h"
#include "core/survey/survey.h"
#include "solvers/similarity_fit.h"

namespace hsmap {
namespace {

struct TruthAtFix {
  SE3d T_W_C;  // true camera pose at the fix time
  SE3d T_W_B;  // true body pose at the fix time
  const InsFixInWorld* fix = nullptr;
};

InsFloor missing(const std::string& why) {
  InsFloor floor;
  floor.rgb_ate_m = MetricValue::missing(why);
  floor.scale_error = MetricValue::missing(why);
  return floor;
}

// The unweighted Umeyama fit, or the identity when the body positions are
// degenerate for it (too few, or collinear): the solver starts from there.
Sim3 initialSimilarity(const std::vector<TruthAtFix>& pairs) {
  std::vector<Eigen::Vector3d> source;
  std::vector<Eigen::Vector3d> target;
  for (const TruthAtFix& pair : pairs) {
    source.push_back(pair.T_W_B.t);
    target.push_back(pair.fix->p_W_B);
  }
  try {
    return alignUmeyama(source, target);
  } catch (const std::invalid_argument&) {
    return Sim3::identity();
  }
}

}  // namespace


InsFloor computeInsFloor(const std::vector<TimedPose>& frames_true,
                         const std::vector<InsFixInWorld>& fixes, const InsConfig& ins) {
  if (frames_true.empty()) throw std::invalid_argument("computeInsFloor: no frames");
  std::vector<double> times;
  std::vector<SE3d> poses;
  for (const TimedPose& frame : frames_true) {
    times.push_back(frame.t);
    poses.push_back(frame.T);
  }
  const TimedPoseTrajectory trajectory(times, poses);
  const SE3d T_C_B = SE3d(ins.T_B_C.rotation, ins.T_B_C.translation_m).inverse();

  // ins.csv has attitude for every fix or for none (csv_table.h).
  const bool with_attitude = !fixes.empty() && fixes.front().q_W_B.has_value();
  std::vector<TruthAtFix> pairs;
  for (const InsFixInWorld& fix : fixes) {
    if (!trajectory.covers(fix.t)) continue;
    if (fix.q_W_B.has_value() != with_attitude) {
      throw std::invalid_argument("computeInsFloor: attitude on some fixes only");
    }
    const SE3d T_W_C = trajectory.at(fix.t);
    pairs.push_back({T_W_C, T_W_C * T_C_B, &fix});
  }
  const std::size_t needed = with_attitude ? 2 : 3;
  if (pairs.size() < needed) {
    return missing(std::to_string(pairs.size()) + " INS fix(es) within the frames' time span [" +
                   formatDouble(trajectory.startTime()) + ", " +
                   formatDouble(trajectory.endTime()) + "] s; need " + std::to_string(needed) +
                   (with_attitude ? " with attitude" : " without attitude") +
                   " to fix a similarity");
  }

  const Eigen::Vector3d sigma_p(ins.sigma_horizontal_m, ins.sigma_horizontal_m, ins.sigma_depth_m);
  const Eigen::Vector3d sigma_a(ins.sigma_attitude_deg[0] * so3_detail::kDegToRad,
                                ins.sigma_attitude_deg[1] * so3_detail::kDegToRad,
                                ins.sigma_attitude_deg[2] * so3_detail::kDegToRad);
  std::vector<SimilarityFitPosition> positions;
  std::vector<SimilarityFitAttitude> attitudes;
  for (const TruthAtFix& pair : pairs) {
    // The similarity moves the camera trajectory (the map); the lever arm
    // to the body is metres, turned with the map but not scaled.
    positions.push_back({pair.T_W_C.t, pair.T_W_C.q * T_C_B.t, pair.fix->p_W_B, sigma_p});
    if (with_attitude) attitudes.push_back({pair.T_W_B.q, *pair.fix->q_W_B, sigma_a});
  }
  Sim3 S;
  try {
    S = fitSimilarity(positions, attitudes, initialSimilarity(pairs)).S_target_source;
  } catch (const std::invalid_argument& error) {
    return missing(std::string("the INS similarity fit failed: ") + error.what());
  }
  const double s = S.scale();
  double sum = 0.0;
  for (const TimedPose& frame : frames_true) {
    sum += (S.apply(frame.T.t) - frame.T.t).squaredNorm();
  }
  InsFloor floor;
  floor.rgb_ate_m = MetricValue::of(std::sqrt(sum / static_cast<double>(frames_true.size())));
  floor.scale_error = MetricValue::of(std::abs(s - 1.0));
  floor.fixes_used = pairs.size();
  floor.S_ins_true = S;
  return floor;
}

}  // namespace hsmap
