#include "pipelines/evaluate/ins_floor.h"

#include <ceres/ceres.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/geometry/pose_interpolation.h"
#include "core/geometry/so3.h"
#include "core/survey/number_text.h"
#include "core/survey/survey.h"

namespace hsmap {
namespace {

// The similarity about the centroid c of the true body positions:
//   p_ins = s R (p - c) + c + t_c,   s = exp(log_s),
// so that R and t_c are nearly uncorrelated (see the header).

// W_p (p_ins - S p_W_B): one fix's position, whitened by its stated sigmas.
struct FixPositionResidual {
  Eigen::Vector3d p_centred;  // p_W_B(t_k) - c
  Eigen::Vector3d p_ins_minus_c;
  Eigen::Vector3d inverse_sigma;

  template <typename T>
  bool operator()(const T* q_data, const T* t_data, const T* log_s, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q(q_data);
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> t(t_data);
    const Eigen::Matrix<T, 3, 1> mapped = ceres::exp(log_s[0]) * (q * p_centred.cast<T>()) + t;
    for (int i = 0; i < 3; ++i) {
      residual[i] = (T(p_ins_minus_c[i]) - mapped[i]) * inverse_sigma[i];
    }
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Vector3d& p_centred,
                                     const Eigen::Vector3d& p_ins_minus_c,
                                     const Eigen::Vector3d& inverse_sigma) {
    return new ceres::AutoDiffCostFunction<FixPositionResidual, 3, 4, 3, 1>(
        new FixPositionResidual{p_centred, p_ins_minus_c, inverse_sigma});
  }
};

// W_a log(R_ins^-1 R R_W_B): one fix's attitude against the turned true attitude.
struct FixAttitudeResidual {
  Eigen::Quaterniond q_ins_inverse;
  Eigen::Quaterniond q_W_B_true;
  Eigen::Vector3d inverse_sigma_rad;

  template <typename T>
  bool operator()(const T* q_data, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> q(q_data);
    const Eigen::Quaternion<T> error =
        q_ins_inverse.cast<T>() * Eigen::Quaternion<T>(q * q_W_B_true.cast<T>());
    const Eigen::Matrix<T, 3, 1> phi = logSO3(error);
    for (int i = 0; i < 3; ++i) residual[i] = phi[i] * inverse_sigma_rad[i];
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Quaterniond& q_ins,
                                     const Eigen::Quaterniond& q_W_B_true,
                                     const Eigen::Vector3d& inverse_sigma_rad) {
    return new ceres::AutoDiffCostFunction<FixAttitudeResidual, 3, 4>(
        new FixAttitudeResidual{q_ins.conjugate(), q_W_B_true, inverse_sigma_rad});
  }
};

struct TruthAtFix {
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
    pairs.push_back({trajectory.at(fix.t) * T_C_B, &fix});
  }
  const std::size_t needed = with_attitude ? 2 : 3;
  if (pairs.size() < needed) {
    return missing(std::to_string(pairs.size()) + " INS fix(es) within the frames' time span [" +
                   formatDouble(trajectory.startTime()) + ", " +
                   formatDouble(trajectory.endTime()) + "] s; need " + std::to_string(needed) +
                   (with_attitude ? " with attitude" : " without attitude") +
                   " to fix a similarity");
  }

  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const TruthAtFix& pair : pairs) c += pair.T_W_B.t;
  c /= static_cast<double>(pairs.size());

  const Sim3 start = initialSimilarity(pairs);
  Eigen::Quaterniond q = start.rotation();
  Eigen::Vector3d t_c = start.scale() * (start.rotation() * c) + start.translation() - c;
  double log_s = std::log(start.scale());

  ceres::Problem problem;
  const Eigen::Vector3d inverse_sigma_p(1.0 / ins.sigma_horizontal_m, 1.0 / ins.sigma_horizontal_m,
                                        1.0 / ins.sigma_depth_m);
  const Eigen::Vector3d inverse_sigma_a(
      1.0 / (ins.sigma_attitude_deg[0] * so3_detail::kDegToRad),
      1.0 / (ins.sigma_attitude_deg[1] * so3_detail::kDegToRad),
      1.0 / (ins.sigma_attitude_deg[2] * so3_detail::kDegToRad));
  for (const TruthAtFix& pair : pairs) {
    problem.AddResidualBlock(FixPositionResidual::create(pair.T_W_B.t - c, pair.fix->p_W_B - c,
                                                         inverse_sigma_p),
                             nullptr, q.coeffs().data(), t_c.data(), &log_s);
    if (with_attitude) {
      problem.AddResidualBlock(
          FixAttitudeResidual::create(*pair.fix->q_W_B, pair.T_W_B.q, inverse_sigma_a), nullptr,
          q.coeffs().data());
    }
  }
  problem.SetManifold(q.coeffs().data(), new ceres::EigenQuaternionManifold);

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;  // 7 unknowns
  options.max_num_iterations = 200;
  // Tight tolerances: the floor of an exact INS is 0, and a test checks it.
  options.function_tolerance = 1e-16;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable()) {
    return missing("the INS similarity fit failed: " + summary.message);
  }

  const double s = std::exp(log_s);
  const Sim3 S(s, q.normalized(), c + t_c - s * (q.normalized() * c));
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
