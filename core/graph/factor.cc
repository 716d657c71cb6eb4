#include "core/graph/factor.h"

#include <algorithm>
#include <stdexcept>

namespace hsmap {

Factor::Factor(std::vector<Key> keys, NoiseModel noise, RobustLoss robust_loss)
    : keys_(std::move(keys)), noise_(std::move(noise)), robust_loss_(robust_loss) {
  if (keys_.empty()) throw std::invalid_argument("Factor: a factor must touch at least one variable");
  std::vector<Key> sorted = keys_;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
    throw std::invalid_argument("Factor: a factor must not name the same variable twice");
  }
}

}  // namespace hsmap
