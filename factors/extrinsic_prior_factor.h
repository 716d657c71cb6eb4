#pragma once
// ExtrinsicPriorFactor: the survey's guess of the RGB-UHI extrinsic
// T_C_U (e.g. from the vehicle's CAD model) as a Gaussian prior on E(0).
//
//   variable   e = T_C_U (pose, [qx qy qz qw tx ty tz])
//   residual   r = [ t_C_U - t_C_U_prior ;                  (3, metres, in C)
//                    log(q_C_U_prior^-1 * q_C_U) ]          (3, radians, in U)
// Why not PosePriorFactor's SE(3) log: survey.yaml gives independent sigmas
// for the translation (sigma_translation_m, on the lever arm as drawn, in C)
// and for the rotation (sigma_rotation_deg); the SE(3) log's rho mixes
// rotation error into the translation part (rho = Jl(phi)^-1 R_prior^T dt),
// so a prior with a large rotation sigma would widen or tilt the translation
// one. The split residual keeps the two independent. The rotation part is a
// right perturbation in U (q_C_U = q_C_U_prior * exp(phi)), the frame in which
// RUN/calibration.yaml reports the rotation's 1-sigma.
// noiseFromSigmas() builds the noise model from the survey's two sigmas.

#include <memory>
#include <string>

#include "core/geometry/se3.h"
#include "core/geometry/so3.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"

namespace hsmap {

// Ceres functor: (pose T_C_U [7]) -> residual [6].
struct ExtrinsicPriorResidual {
  SE3d T_C_U_prior;

  template <class T>
  bool operator()(const T* extrinsic_T_C_U, T* residual) const {
    const Eigen::Quaternion<T> q_C_U(extrinsic_T_C_U[3], extrinsic_T_C_U[0], extrinsic_T_C_U[1],
                                     extrinsic_T_C_U[2]);
    for (int i = 0; i < 3; ++i) residual[i] = extrinsic_T_C_U[4 + i] - T_C_U_prior.t[i];
    const Vector3<T> phi = logSO3(T_C_U_prior.q.conjugate().cast<T>() * q_C_U);
    for (int i = 0; i < 3; ++i) residual[3 + i] = phi[i];
    return true;
  }
};

class ExtrinsicPriorFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 6;

  // Diagonal noise model [sigma_t, sigma_t, sigma_t, sigma_r, sigma_r, sigma_r]
  // with sigma_r = sigma_rotation_deg * pi / 180 (radians). Throws
  // std::invalid_argument for a sigma that is not a positive finite number.
  static NoiseModel noiseFromSigmas(double sigma_rotation_deg, double sigma_translation_m);

  // Throws std::invalid_argument for a noise model that is not 6-dimensional
  // or a prior whose rotation is not a unit quaternion.
  ExtrinsicPriorFactor(Key extrinsic_T_C_U, const SE3d& T_C_U_prior, NoiseModel noise);

  std::string name() const override { return "ExtrinsicPriorFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const SE3d& prior() const { return T_C_U_prior_; }

 private:
  SE3d T_C_U_prior_;
};

}  // namespace hsmap
