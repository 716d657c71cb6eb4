#pragma once
// FactorGraph: the factors of an estimation problem, indexed by the variables
// they touch. A container only: it does not evaluate or solve anything (see
// solvers/), so pipelines and researchers can build, inspect and combine
// graphs without a solver in sight.

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/graph/factor.h"
#include "core/graph/values.h"

namespace hsmap {

class FactorGraph {
 public:
  using FactorIndex = std::size_t;

  FactorIndex add(std::shared_ptr<const Factor> factor);
  template <class F, class... Args>
  FactorIndex emplace(Args&&... args) {
    return add(std::make_shared<const F>(std::forward<Args>(args)...));
  }

  std::size_t size() const { return factors_.size(); }
  const std::shared_ptr<const Factor>& factor(FactorIndex i) const { return factors_.at(i); }
  const std::vector<std::shared_ptr<const Factor>>& factors() const { return factors_; }

  // Indices of the factors that touch `key` (empty if none).
  const std::vector<FactorIndex>& factorsOf(Key key) const;
  // Every variable touched by at least one factor, in key order.
  std::vector<Key> keys() const;
  // Variables touched by factors but absent from `values` (a graph cannot be
  // solved until this is empty).
  std::vector<Key> missingKeys(const Values& values) const;
  // Total residual dimension of all factors.
  std::size_t residualDimension() const { return residual_dimension_; }
  // Factor count per factor name, e.g. {"ReprojectionFactor": 5000, ...}.
  std::map<std::string, std::size_t> countByName() const;

 private:
  std::vector<std::shared_ptr<const Factor>> factors_;
  std::map<Key, std::vector<FactorIndex>> factors_by_key_;
  std::size_t residual_dimension_ = 0;
};

}  // namespace hsmap
