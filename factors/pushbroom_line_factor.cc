#include "factors/pushbroom_line_factor.h"

#include <ceres/autodiff_cost_function.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "factors/factor_argument_checks.h"

namespace hsmap {

namespace {

constexpr const char* kName = "PushbroomLineFactor";

// j such that S(j) .. S(j+4) span the two segments around the initial
// exposure time with the most margin (see the header comment).
int windowStart(const SplineTiming& spline, double t_recorded, double time_offset_guess_s) {
  requireFinite(kName, "recorded time", t_recorded);
  requireFinite(kName, "time offset guess", time_offset_guess_s);
  if (spline.num_control_points < PushbroomLineFactor::kNumControlPoints) {
    throw std::invalid_argument(std::string(kName) +
                                ": the spline needs at least 5 control points (the factor spans "
                                "two segments), got " +
                                std::to_string(spline.num_control_points));
  }
  const SplineSegment segment = spline.segmentAt(t_recorded + time_offset_guess_s);
  const int first = segment.u < 0.5 ? segment.first_control_point - 1 : segment.first_control_point;
  return std::clamp(first, 0, spline.num_control_points - PushbroomLineFactor::kNumControlPoints);
}

std::vector<Key> windowKeys(int first, Key extrinsic_T_C_U, Key time_offset_d) {
  std::vector<Key> keys;
  for (int k = 0; k < PushbroomLineFactor::kNumControlPoints; ++k) {
    keys.push_back(S(static_cast<std::uint64_t>(first + k)));
  }
  keys.push_back(extrinsic_T_C_U);
  keys.push_back(time_offset_d);
  return keys;
}

std::vector<Key> withLandmark(std::vector<Key> keys, Key landmark_p_W) {
  keys.push_back(landmark_p_W);
  return keys;
}

}  // namespace

PushbroomLineFactor::PushbroomLineFactor(const SplineTiming& spline, double time_offset_guess_s,
                                         Key extrinsic_T_C_U, Key time_offset_d,
                                         Key landmark_p_W, const PushbroomObservation& observation,
                                         const PushbroomParameters& camera, NoiseModel noise,
                                         RobustLoss robust_loss)
    : PushbroomLineFactor(
          spline, windowStart(spline, observation.t_recorded, time_offset_guess_s),
          withLandmark(windowKeys(windowStart(spline, observation.t_recorded, time_offset_guess_s),
                                  extrinsic_T_C_U, time_offset_d),
                       landmark_p_W),
          std::nullopt, observation, camera, std::move(noise), robust_loss) {}

PushbroomLineFactor::PushbroomLineFactor(const SplineTiming& spline, double time_offset_guess_s,
                                         Key extrinsic_T_C_U, Key time_offset_d,
                                         const Eigen::Vector3d& p_W,
                                         const PushbroomObservation& observation,
                                         const PushbroomParameters& camera, NoiseModel noise,
                                         RobustLoss robust_loss)
    : PushbroomLineFactor(
          spline, windowStart(spline, observation.t_recorded, time_offset_guess_s),
          windowKeys(windowStart(spline, observation.t_recorded, time_offset_guess_s),
                     extrinsic_T_C_U, time_offset_d),
          p_W, observation, camera, std::move(noise), robust_loss) {
  requireFinite(kName, "fixed point p_W", p_W);
}

PushbroomLineFactor::PushbroomLineFactor(const SplineTiming& spline, int first_control_point,
                                         std::vector<Key> keys,
                                         std::optional<Eigen::Vector3d> p_W_fixed,
                                         const PushbroomObservation& observation,
                                         const PushbroomParameters& camera, NoiseModel noise,
                                         RobustLoss robust_loss)
    : CeresFactor(std::move(keys), std::move(noise), robust_loss),
      spline_(spline),
      first_control_point_(first_control_point),
      p_W_fixed_(std::move(p_W_fixed)),
      observation_(observation),
      intrinsics_(PushbroomCamera(camera).intrinsics()) {
  requireNoiseDimension(kName, this->noise(), kResidualDimension);
  requireFinite(kName, "observed pixel u", observation_.u);
}

std::pair<double, double> PushbroomLineFactor::coveredTimeRange() const {
  return {spline_.t0 + first_control_point_ * spline_.dt,
          spline_.t0 + (first_control_point_ + 2) * spline_.dt};
}

bool PushbroomLineFactor::coversTimeOffset(double d) const {
  const auto [begin, end] = coveredTimeRange();
  const double t = observation_.t_recorded + d;
  return t >= begin && t <= end;
}

std::unique_ptr<ceres::CostFunction> PushbroomLineFactor::createCostFunction() const {
  constexpr int P = SE3d::kNumParameters;
  const PushbroomLineResidual residual{
      (observation_.t_recorded - spline_.t0) / spline_.dt - first_control_point_,
      1.0 / spline_.dt, observation_.u, intrinsics_,
      p_W_fixed_.value_or(Eigen::Vector3d(Eigen::Vector3d::Zero()))};
  if (p_W_fixed_) {
    return std::make_unique<ceres::AutoDiffCostFunction<PushbroomLineResidual, kResidualDimension,
                                                        P, P, P, P, P, P, 1>>(
        new PushbroomLineResidual(residual));
  }
  return std::make_unique<ceres::AutoDiffCostFunction<PushbroomLineResidual, kResidualDimension, P,
                                                      P, P, P, P, P, 1, 3>>(
      new PushbroomLineResidual(residual));
}

}  // namespace hsmap
