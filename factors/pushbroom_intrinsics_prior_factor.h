#pragma once
// PushbroomIntrinsicsPriorFactor: the survey's UHI camera (survey.yaml's
// uhi.camera) as a Gaussian prior on the intrinsics block [f cx k1 k2]
// (PushbroomCamera::kNumIntrinsics) that self-calibrating tie points share,
// with each parameter's 1-sigma from uhi.camera_sigma.
//
//   variable   k = K(0) (vector of 4: f, cx in pixels; k1, k2 unitless)
//   residual   r = k[i] - prior[i] for every i whose sigma is > 0
//              (dimension: the number of such parameters, 1..4)
// A sigma of 0 means "held at the prior": that parameter has no residual
// here, and the caller keeps it constant in the solve (GraphProblemOptions::
// constant_components; the whole block constant when every sigma is 0, in
// which case this factor is not built at all). noise() is built from the
// positive sigmas, in parameter order.
//
// Jacobian: analytic, the rows of the identity of the free parameters.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry/pushbroom_camera.h"
#include "core/graph/key.h"
#include "factors/ceres_factor.h"

namespace hsmap {

class PushbroomIntrinsicsPriorFactor : public CeresFactor {
 public:
  using Intrinsics = std::array<double, PushbroomCamera::kNumIntrinsics>;

  // Throws std::invalid_argument for a non-finite prior, a negative or
  // non-finite sigma, or sigmas that are all 0 (nothing to estimate).
  PushbroomIntrinsicsPriorFactor(Key uhi_intrinsics, const Intrinsics& prior, const Intrinsics& sigmas);

  std::string name() const override { return "PushbroomIntrinsicsPriorFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const Intrinsics& prior() const { return prior_; }
  // Indices (into [f cx k1 k2]) of the parameters with a sigma > 0, the
  // residual's order.
  const std::vector<int>& freeParameters() const { return free_; }
  // Indices of the parameters with a sigma of 0 (to be held constant).
  static std::vector<int> heldParameters(const Intrinsics& sigmas);

 private:
  Intrinsics prior_;
  std::vector<int> free_;
};

}  // namespace hsmap
