#include "core/graph/factor_graph.h"

#include <stdexcept>

namespace hsmap {

FactorGraph::FactorIndex FactorGraph::add(std::shared_ptr<const Factor> factor) {
  if (!factor) throw std::invalid_argument("FactorGraph: cannot add a null factor");
  const FactorIndex index = factors_.size();
  for (const Key& key : factor->keys()) factors_by_key_[key].push_back(index);
  residual_dimension_ += static_cast<std::size_t>(factor->residualDimension());
  factors_.push_back(std::move(factor));
  return index;
}

const std::vector<FactorGraph::FactorIndex>& FactorGraph::factorsOf(Key key) const {
  static const std::vector<FactorIndex> kNone;
  const auto it = factors_by_key_.find(key);
  return it == factors_by_key_.end() ? kNone : it->second;
}

std::vector<Key> FactorGraph::keys() const {
  std::vector<Key> result;
  result.reserve(factors_by_key_.size());
  for (const auto& [key, indices] : factors_by_key_) result.push_back(key);
  return result;
}

std::vector<Key> FactorGraph::missingKeys(const Values& values) const {
  std::vector<Key> missing;
  for (const auto& [key, indices] : factors_by_key_) {
    if (!values.contains(key)) missing.push_back(key);
  }
  return missing;
}

std::map<std::string, std::size_t> FactorGraph::countByName() const {
  std::map<std::string, std::size_t> counts;
  for (const auto& factor : factors_) ++counts[factor->name()];
  return counts;
}

}  // namespace hsmap
