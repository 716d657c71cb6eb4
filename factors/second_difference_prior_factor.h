#pragma once
// SecondDifferencePriorFactor: a smoothness prior on a quantity sampled at
// three neighbouring, evenly spaced points (e.g. the water's attenuation c(λ)
// in three neighbouring UHI bands): its second difference is near zero.
//
//   variables  a, b, c (scalars: the values at x − h, x, x + h)
//   residual   r = a − 2 b + c                             (1)
// With the noise model's sigma s the prior says the curve's second
// derivative is within s / h² (1-sigma): a smooth curve may still bend, a
// band that the data leave undetermined follows its neighbours.

#include <memory>
#include <string>

#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"

namespace hsmap {

// Ceres functor: (a [1], b [1], c [1]) -> residual [1].
struct SecondDifferenceResidual {
  template <class T>
  bool operator()(const T* a, const T* b, const T* c, T* residual) const {
    residual[0] = a[0] - 2.0 * b[0] + c[0];
    return true;
  }
};

class SecondDifferencePriorFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 1;

  // Throws std::invalid_argument for a noise model that is not 1-dimensional.
  SecondDifferencePriorFactor(Key a, Key b, Key c, NoiseModel noise);

  std::string name() const override { return "SecondDifferencePriorFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;
};

}  // namespace hsmap
