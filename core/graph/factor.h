#pragma once
// Factor: one measurement of the factor graph. It names the variables it
// touches (its keys, in the order its residual takes them), the Gaussian noise
// of its residual and an optional robust loss. It knows nothing about how the
// graph is solved: the Ceres residual of each concrete factor lives in
// factors/, and solvers/ turns a graph into a Ceres problem.

#include <memory>
#include <string>
#include <vector>

#include "core/graph/key.h"
#include "core/graph/noise_model.h"

namespace hsmap {

class Factor {
 public:
  virtual ~Factor() = default;

  const std::vector<Key>& keys() const { return keys_; }
  const NoiseModel& noise() const { return noise_; }
  const RobustLoss& robustLoss() const { return robust_loss_; }
  int residualDimension() const { return noise_.dimension(); }

  // What the factor measures, e.g. "InsPositionFactor"; used in summaries.
  virtual std::string name() const = 0;

 protected:
  Factor(std::vector<Key> keys, NoiseModel noise, RobustLoss robust_loss);

 private:
  std::vector<Key> keys_;
  NoiseModel noise_;
  RobustLoss robust_loss_;
};

}  // namespace hsmap
