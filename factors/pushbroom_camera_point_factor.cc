#include "factors/pushbroom_camera_point_factor.h"

#include <ceres/autodiff_cost_function.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "factors/factor_argument_checks.h"

namespace hsmap {

namespace {

constexpr const char* kName = "PushbroomCameraPointFactor";
constexpr int P = SE3d::kNumParameters;
constexpr int kIntrinsics = PushbroomCamera::kNumIntrinsics;

}  // namespace

std::vector<Key> PushbroomCameraPointFactor::keysFor(const SplineTiming& spline,
                                                     double time_offset_guess_s, Key extrinsic_T_C_U,
                                                     Key time_offset_d,
                                                     const std::optional<Key>& uhi_intrinsics,
                                                     const PushbroomObservation& observation) {
  std::vector<Key> keys = PushbroomLineFactor::windowKeysFor(
      PushbroomLineFactor::windowStartFor(spline, observation.t_recorded, time_offset_guess_s),
      extrinsic_T_C_U, time_offset_d);
  if (uhi_intrinsics) keys.push_back(*uhi_intrinsics);
  return keys;
}

PushbroomCameraPointFactor::PushbroomCameraPointFactor(
    const SplineTiming& spline, double time_offset_guess_s, Key extrinsic_T_C_U, Key time_offset_d,
    double t_reference, const Eigen::Vector3d& p_C, const PushbroomObservation& observation,
    const PushbroomParameters& camera, NoiseModel noise, RobustLoss robust_loss)
    : PushbroomCameraPointFactor(spline, time_offset_guess_s, extrinsic_T_C_U, time_offset_d,
                                 std::nullopt, t_reference, p_C, observation, camera,
                                 std::move(noise), robust_loss) {}

PushbroomCameraPointFactor::PushbroomCameraPointFactor(
    const SplineTiming& spline, double time_offset_guess_s, Key extrinsic_T_C_U, Key time_offset_d,
    Key uhi_intrinsics, double t_reference, const Eigen::Vector3d& p_C,
    const PushbroomObservation& observation, const PushbroomParameters& camera, NoiseModel noise,
    RobustLoss robust_loss)
    : PushbroomCameraPointFactor(spline, time_offset_guess_s, extrinsic_T_C_U, time_offset_d,
                                 std::optional<Key>(uhi_intrinsics), t_reference, p_C, observation,
                                 camera, std::move(noise), robust_loss) {}

PushbroomCameraPointFactor::PushbroomCameraPointFactor(
    const SplineTiming& spline, double time_offset_guess_s, Key extrinsic_T_C_U, Key time_offset_d,
    const std::optional<Key>& uhi_intrinsics, double t_reference, const Eigen::Vector3d& p_C,
    const PushbroomObservation& observation, const PushbroomParameters& camera, NoiseModel noise,
    RobustLoss robust_loss)
    : CeresFactor(keysFor(spline, time_offset_guess_s, extrinsic_T_C_U, time_offset_d, uhi_intrinsics,
                          observation),
                  std::move(noise), robust_loss),
      spline_(spline),
      first_control_point_(
          PushbroomLineFactor::windowStartFor(spline, observation.t_recorded, time_offset_guess_s)),
      t_reference_(t_reference),
      p_C_(p_C),
      observation_(observation),
      camera_(camera),
      estimates_intrinsics_(uhi_intrinsics.has_value()) {
  requireNoiseDimension(kName, this->noise(), kResidualDimension);
  requireFinite(kName, "observed pixel u", observation_.u);
  requireFinite(kName, "point p_C", p_C_);
  requireFinite(kName, "reference time", t_reference_);
  const double begin = spline_.t0 + first_control_point_ * spline_.dt;
  const double end = begin + 2.0 * spline_.dt;
  if (t_reference < begin || t_reference > end) {
    throw std::out_of_range(std::string(kName) + ": reference time " + std::to_string(t_reference) +
                            " s is outside the factor's window [" + std::to_string(begin) + ", " +
                            std::to_string(end) + "] s");
  }
}

PushbroomCameraPointResidual PushbroomCameraPointFactor::residual() const {
  const double j = first_control_point_;
  return PushbroomCameraPointResidual{
      PushbroomLineResidual{(observation_.t_recorded - spline_.t0) / spline_.dt - j,
                            1.0 / spline_.dt, observation_.u, camera_.intrinsics(),
                            Eigen::Vector3d::Zero()},
      (t_reference_ - spline_.t0) / spline_.dt - j, p_C_};
}

std::unique_ptr<ceres::CostFunction> PushbroomCameraPointFactor::createCostFunction() const {
  if (estimates_intrinsics_) {
    return std::make_unique<ceres::AutoDiffCostFunction<PushbroomCameraPointIntrinsicsResidual,
                                                        kResidualDimension, P, P, P, P, P, P, 1, kIntrinsics>>(
        new PushbroomCameraPointIntrinsicsResidual{residual()});
  }
  return std::make_unique<ceres::AutoDiffCostFunction<PushbroomCameraPointResidual,
                                                      kResidualDimension, P, P, P, P, P, P, 1>>(
      new PushbroomCameraPointResidual(residual()));
}

}  // namespace hsmap
