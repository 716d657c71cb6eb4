#include "factors/pushbroom_line_factor.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/sized_cost_function.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/geometry/se3_bspline_jacobians.h"
#include "factors/factor_argument_checks.h"
#include "factors/pose_block_jacobian.h"
#include "factors/world_point_projection_jacobians.h"

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

constexpr int P = SE3d::kNumParameters;
constexpr int kWindow = PushbroomLineFactor::kNumControlPoints;
constexpr int kExtrinsicBlock = kWindow;
constexpr int kTimeOffsetBlock = kWindow + 1;
constexpr int kLandmarkBlock = kWindow + 2;

template <bool kWithLandmark>
using PushbroomLineCostBase =
    std::conditional_t<kWithLandmark,
                       ceres::SizedCostFunction<PushbroomLineFactor::kResidualDimension, P, P, P,
                                                P, P, P, 1, 3>,
                       ceres::SizedCostFunction<PushbroomLineFactor::kResidualDimension, P, P, P,
                                                P, P, P, 1>>;

// PushbroomLineResidual with analytic Jacobians (see the header comment):
// blocks S(j..j+4), T_C_U, d [, p_W].
template <bool kWithLandmark>
class PushbroomLineCost final : public PushbroomLineCostBase<kWithLandmark> {
 public:
  PushbroomLineCost(double s_recorded, double inverse_dt, double u_measured,
                    const PushbroomCamera& camera, const Eigen::Vector3d& p_W_fixed)
      : s_recorded_(s_recorded),
        inverse_dt_(inverse_dt),
        u_measured_(u_measured),
        camera_(camera),
        p_W_fixed_(p_W_fixed) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    // The segment choice of PushbroomLineResidual::predict(), same arithmetic.
    const double s = s_recorded_ + parameters[kTimeOffsetBlock][0] * inverse_dt_;
    const int segment = s < 1.0 ? 0 : 1;
    const double u = s - double(segment);
    const SE3d T_C_U = SE3d::fromParameters(parameters[kExtrinsicBlock]);
    const Eigen::Vector3d p_W =
        kWithLandmark ? Eigen::Vector3d(parameters[kLandmarkBlock][0],
                                        parameters[kLandmarkBlock][1],
                                        parameters[kLandmarkBlock][2])
                      : p_W_fixed_;
    if (jacobians == nullptr) {
      // Residual only (line search, cost checks): the pose alone is cheaper.
      const Eigen::Vector2d predicted = projectPushbroom(
          evaluateSe3Spline(parameters + segment, u) * T_C_U, p_W, camera_.intrinsics().data());
      residuals[0] = predicted.x() - u_measured_;
      residuals[1] = predicted.y();
      return true;
    }
    const SE3SplineJacobians spline = SE3SplineJacobians::fromBlocks(parameters + segment, u);
    const SE3d T_W_U = spline.pose() * T_C_U;
    ProjectionJacobians projection;
    const Eigen::Vector2d predicted = projectWithJacobians(camera_, T_W_U, p_W, &projection);
    residuals[0] = predicted.x() - u_measured_;
    residuals[1] = predicted.y();

    // G_C: the residual under T_W_C exp(xi), i.e. T_W_U exp(Ad(T_C_U^-1) xi).
    const Eigen::Matrix<double, 2, 6> d_r_d_T_W_C =
        projection.d_pose * T_C_U.inverse().adjoint();
    bool any_control_point = false;
    for (int k = 0; k < kWindow; ++k) any_control_point |= jacobians[k] != nullptr;
    if (any_control_point) {
      std::array<Eigen::Matrix<double, 2, 6>, 4> d_r_d_control_points;
      spline.chain<2>(d_r_d_T_W_C, &d_r_d_control_points);
      for (int k = 0; k < kWindow; ++k) {
        if (jacobians[k] == nullptr) continue;
        const int in_segment = k - segment;
        if (in_segment < 0 || in_segment > 3) {
          // Not active in the current segment.
          Eigen::Map<Eigen::Matrix<double, 2, P, Eigen::RowMajor>> inactive(jacobians[k]);
          inactive.setZero();
          continue;
        }
        poseTangentToAmbientJacobian<2>(SE3d::fromParameters(parameters[k]),
                                        d_r_d_control_points[in_segment], jacobians[k]);
      }
    }
    if (jacobians[kExtrinsicBlock] != nullptr) {
      poseTangentToAmbientJacobian<2>(T_C_U, projection.d_pose, jacobians[kExtrinsicBlock]);
    }
    if (jacobians[kTimeOffsetBlock] != nullptr) {
      Eigen::Map<Eigen::Vector2d> d_r_d_d(jacobians[kTimeOffsetBlock]);
      d_r_d_d = d_r_d_T_W_C * spline.bodyTwistPerUnitU() * inverse_dt_;
    }
    if constexpr (kWithLandmark) {
      if (jacobians[kLandmarkBlock] != nullptr) {
        Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> d_r_d_p_W(
            jacobians[kLandmarkBlock]);
        d_r_d_p_W = projection.d_point;
      }
    }
    return true;
  }

 private:
  double s_recorded_;  // (t_recorded - t0) / dt - j
  double inverse_dt_;
  double u_measured_;
  PushbroomCamera camera_;
  Eigen::Vector3d p_W_fixed_;  // the fixed-point form only
};

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
      camera_(camera) {
  requireNoiseDimension(kName, this->noise(), kResidualDimension);
  requireFinite(kName, "observed pixel u", observation_.u);
}

int PushbroomLineFactor::windowStartFor(const SplineTiming& spline, double t_recorded,
                                        double time_offset_guess_s) {
  return windowStart(spline, t_recorded, time_offset_guess_s);
}

std::vector<Key> PushbroomLineFactor::windowKeysFor(int first, Key extrinsic_T_C_U, Key time_offset_d) {
  return windowKeys(first, extrinsic_T_C_U, time_offset_d);
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
  const double s_recorded =
      (observation_.t_recorded - spline_.t0) / spline_.dt - first_control_point_;
  const Eigen::Vector3d p_W_fixed = p_W_fixed_.value_or(Eigen::Vector3d(Eigen::Vector3d::Zero()));
  if (p_W_fixed_) {
    return std::make_unique<PushbroomLineCost<false>>(s_recorded, 1.0 / spline_.dt,
                                                      observation_.u, camera_, p_W_fixed);
  }
  return std::make_unique<PushbroomLineCost<true>>(s_recorded, 1.0 / spline_.dt, observation_.u,
                                                   camera_, p_W_fixed);
}

std::unique_ptr<ceres::CostFunction> PushbroomLineFactor::createAutoDiffCostFunction() const {
  const PushbroomLineResidual residual{
      (observation_.t_recorded - spline_.t0) / spline_.dt - first_control_point_,
      1.0 / spline_.dt, observation_.u, camera_.intrinsics(),
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
