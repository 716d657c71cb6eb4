#pragma once
// TimeOffsetPriorFactor: the survey's guess of the UHI time offset d
// (true UHI time = recorded time + d, DATASET.md) as a Gaussian prior on D(0).
//
//   variable   d (scalar, seconds)
//   residual   r = d - prior_s                             (1, seconds)
// With survey.yaml's uhi.time_offset_s and time_offset_sigma_s the noise model
// is NoiseModel::isotropic(1, time_offset_sigma_s).

#include <memory>
#include <string>

#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"

namespace hsmap {

// Ceres functor: (d [1]) -> residual [1].
struct TimeOffsetPriorResidual {
  double prior_s;

  template <class T>
  bool operator()(const T* time_offset_d, T* residual) const {
    residual[0] = time_offset_d[0] - prior_s;
    return true;
  }
};

class TimeOffsetPriorFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 1;

  // Throws std::invalid_argument for a noise model that is not 1-dimensional
  // or a non-finite prior.
  TimeOffsetPriorFactor(Key time_offset_d, double prior_s, NoiseModel noise);

  std::string name() const override { return "TimeOffsetPriorFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  double prior() const { return prior_s_; }

 private:
  double prior_s_;
};

}  // namespace hsmap
