#include "pipelines/surface/surface_cut_options.h"

#include <cmath>

namespace hsmap {

std::string SurfaceCutOptions::validate() const {
  if (!(visibility_weight > 0.0 && std::isfinite(visibility_weight)))
    return "visibility_weight must be finite and > 0";
  if (!(noise_sigma >= 0.0 && std::isfinite(noise_sigma)))
    return "noise_sigma must be finite and >= 0 (metres; 0 = hard visibility)";
  if (!(area_weight >= 0.0 && std::isfinite(area_weight)))
    return "area_weight must be finite and >= 0";
  if (!(prior_weight >= 0.0 && std::isfinite(prior_weight)))
    return "prior_weight must be finite and >= 0";
  if (max_cells_per_ray < 1) return "max_cells_per_ray must be >= 1";
  return {};
}

}  // namespace hsmap
