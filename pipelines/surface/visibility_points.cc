#include "pipelines/surface/visibility_points.h"

#include <cmath>

namespace hsmap {

std::string VisibilityPoints::validate() const {
  if (views.size() != p_W.size())
    return "views has " + std::to_string(views.size()) + " entries for " +
           std::to_string(p_W.size()) + " points (one list of cameras per point)";
  if (!weights.empty() && weights.size() != p_W.size())
    return "weights has " + std::to_string(weights.size()) + " entries for " +
           std::to_string(p_W.size()) + " points (empty or one per point)";
  for (std::size_t k = 0; k < c_W.size(); ++k)
    if (!c_W[k].allFinite()) return "camera centre " + std::to_string(k) + " is not finite";
  for (std::size_t i = 0; i < p_W.size(); ++i) {
    if (!p_W[i].allFinite()) return "point " + std::to_string(i) + " is not finite";
    if (!weights.empty() && !(weights[i] > 0.0 && std::isfinite(weights[i])))
      return "point " + std::to_string(i) + " has weight " + std::to_string(weights[i]) +
             " (must be finite and > 0)";
    for (int k : views[i]) {
      if (k < 0 || static_cast<std::size_t>(k) >= c_W.size())
        return "point " + std::to_string(i) + " names camera " + std::to_string(k) + " of " +
               std::to_string(c_W.size());
      if (c_W[k] == p_W[i])
        return "point " + std::to_string(i) + " lies at the centre of camera " + std::to_string(k);
    }
  }
  return {};
}

}  // namespace hsmap
