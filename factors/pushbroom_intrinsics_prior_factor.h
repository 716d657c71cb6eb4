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
// A ParameterSubsetPriorFactor on that block (its residual, noise and
// analytic Jacobian).

#include <array>
#include <vector>

#include "core/geometry/pushbroom_camera.h"
#include "core/graph/key.h"
#include "factors/parameter_subset_prior_factor.h"

namespace hsmap {

class PushbroomIntrinsicsPriorFactor : public ParameterSubsetPriorFactor {
 public:
  using Intrinsics = std::array<double, PushbroomCamera::kNumIntrinsics>;

  // Throws std::invalid_argument for a non-finite prior, a negative or
  // non-finite sigma, or sigmas that are all 0 (nothing to estimate).
  PushbroomIntrinsicsPriorFactor(Key uhi_intrinsics, const Intrinsics& prior, const Intrinsics& sigmas)
      : ParameterSubsetPriorFactor("PushbroomIntrinsicsPriorFactor", uhi_intrinsics, {prior.begin(), prior.end()},
                                   {sigmas.begin(), sigmas.end()}) {}

  // Indices of the parameters with a sigma of 0 (to be held constant).
  static std::vector<int> heldParameters(const Intrinsics& sigmas) {
    return heldComponents({sigmas.begin(), sigmas.end()});
  }
};

}  // namespace hsmap
