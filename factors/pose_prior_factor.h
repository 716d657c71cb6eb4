#pragma once
// PosePriorFactor: a Gaussian prior on a pose variable (any T_A_B: a keyframe
// pose, a spline control point, an extrinsic), e.g. to fix the gauge.
//
//   variable   x = T (pose, [qx qy qz qw tx ty tz])
//   residual   r = log(prior^-1 * T) = [rho; phi]          (6)
// with se3.h's log, TRANSLATION FIRST: rho (metres) and phi (radians), both
// expressed in the pose's own frame B (right perturbation: T = prior *
// exp(r)), the same tangent space as the solver's SE(3) manifold, so the
// noise model's 6x6 covariance is a covariance of that right perturbation.
// Note rho = Jl(phi)^-1 (t - t_prior rotated into B), which differs from the
// plain translation error by a term of second order in the error;
// ExtrinsicPriorFactor (extrinsic_prior_factor.h) uses the plain translation
// instead, to match a survey's per-component sigmas.

#include <memory>
#include <string>

#include "core/geometry/se3.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"

namespace hsmap {

// Ceres functor: (pose T [7]) -> residual [6].
struct PosePriorResidual {
  SE3d prior_inverse;

  template <class T>
  bool operator()(const T* pose, T* residual) const {
    const Vector6<T> r = (prior_inverse.cast<T>() * SE3<T>::fromParameters(pose)).log();
    for (int i = 0; i < 6; ++i) residual[i] = r[i];
    return true;
  }
};

class PosePriorFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 6;

  // Throws std::invalid_argument for a noise model that is not 6-dimensional
  // or a prior whose rotation is not a unit quaternion.
  PosePriorFactor(Key pose, const SE3d& prior, NoiseModel noise,
                  RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "PosePriorFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const SE3d& prior() const { return prior_; }

 private:
  SE3d prior_;
};

}  // namespace hsmap
