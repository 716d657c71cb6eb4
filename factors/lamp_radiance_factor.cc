#include "factors/lamp_radiance_factor.h"

#include <ceres/autodiff_cost_function.h>

#include <stdexcept>
#include <string>

#include "factors/factor_argument_checks.h"

namespace hsmap {

LampRadianceFactor::LampRadianceFactor(Key attenuation, Key backscatter, Key log_reflectance, Key beam,
                                       LampRadianceResidual measurement, NoiseModel noise, RobustLoss loss)
    : CeresFactor({attenuation, backscatter, log_reflectance, beam}, std::move(noise), loss),
      measurement_(std::move(measurement)) {
  const char* name = "LampRadianceFactor";
  requireNoiseDimension(name, this->noise(), kResidualDimension);
  requireFinite(name, "dn", measurement_.dn);
  requireFinite(name, "response_dn", measurement_.response_dn);
  requireFinite(name, "uhi_range_m", measurement_.uhi_range_m);
  if (!(measurement_.response_dn > 0.0)) {
    throw std::invalid_argument(std::string(name) + ": response_dn must be > 0, got " +
                                std::to_string(measurement_.response_dn));
  }
  if (!(measurement_.uhi_range_m > 0.0)) {
    throw std::invalid_argument(std::string(name) + ": uhi_range_m must be > 0, got " +
                                std::to_string(measurement_.uhi_range_m));
  }
  if (measurement_.lamps.empty()) throw std::invalid_argument(std::string(name) + ": no lamp lights the point");
  for (const LampPath& lamp : measurement_.lamps) {
    if (!(lamp.range_m > 0.0) || !std::isfinite(lamp.range_m) || !(lamp.cos_incidence > 0.0) ||
        !(lamp.cos_incidence <= 1.0) || !(lamp.off_axis_rad >= 0.0) || !(lamp.off_axis_rad <= M_PI)) {
      throw std::invalid_argument(std::string(name) +
                                  ": a lamp path needs range_m > 0, cos_incidence in (0, 1] and "
                                  "off_axis_rad in [0, pi], got " +
                                  std::to_string(lamp.range_m) + ", " + std::to_string(lamp.cos_incidence) +
                                  ", " + std::to_string(lamp.off_axis_rad));
    }
  }
}

std::unique_ptr<ceres::CostFunction> LampRadianceFactor::createCostFunction() const {
  return std::make_unique<
      ceres::AutoDiffCostFunction<LampRadianceResidual, kResidualDimension, 1, 1, 1, kLampBeamCoefficients>>(
      new LampRadianceResidual(measurement_));
}

}  // namespace hsmap
