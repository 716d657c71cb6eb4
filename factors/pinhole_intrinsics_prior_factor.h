#pragma once
// PinholeIntrinsicsPriorFactor: the survey's RGB camera (survey.yaml's
// rgb.camera) as a Gaussian prior on the intrinsics block
// [fx fy cx cy k1 k2 p1 p2 k3] (PinholeRadtanCamera::kNumIntrinsics, OpenCV's
// order) that self-calibrating reprojections share
// (ReprojectionWithIntrinsicsFactor), with each parameter's 1-sigma from
// rgb.camera_sigma. The RGB twin of PushbroomIntrinsicsPriorFactor.
//
//   variable   k = K(i) (vector of 9: fx, fy, cx, cy in pixels; k1, k2, p1, p2, k3 unitless)
//   residual   r = k[j] - prior[j] for every j whose sigma is > 0
//              (dimension: the number of such parameters, 1..9)
// A sigma of 0 means "held at the prior": that parameter has no residual
// here, and the caller keeps it constant in the solve (GraphProblemOptions::
// constant_components, heldParameters()); with every sigma 0 the factor is
// not built at all (nothing to estimate). noise() is built from the positive
// sigmas, in parameter order.
//
// A ParameterSubsetPriorFactor on that block (its residual, noise and
// analytic Jacobian).

#include <array>
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/graph/key.h"
#include "factors/parameter_subset_prior_factor.h"

namespace hsmap {

class PinholeIntrinsicsPriorFactor : public ParameterSubsetPriorFactor {
 public:
  using Intrinsics = std::array<double, PinholeRadtanCamera::kNumIntrinsics>;

  // Throws std::invalid_argument for a non-finite prior, a negative or
  // non-finite sigma, or sigmas that are all 0 (nothing to estimate).
  PinholeIntrinsicsPriorFactor(Key rgb_intrinsics, const Intrinsics& prior, const Intrinsics& sigmas)
      : ParameterSubsetPriorFactor("PinholeIntrinsicsPriorFactor", rgb_intrinsics, {prior.begin(), prior.end()},
                                   {sigmas.begin(), sigmas.end()}) {}

  // Indices of the parameters with a sigma of 0 (to be held constant).
  static std::vector<int> heldParameters(const Intrinsics& sigmas) {
    return heldComponents({sigmas.begin(), sigmas.end()});
  }
};

}  // namespace hsmap
