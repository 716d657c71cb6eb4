#include "pipelines/simulate/water_backscatter.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <tbb/parallel_for.h>

namespace hsmap {

double henyeyGreenstein(double cos_psi, double g) {
  const double denominator = 1.0 + g * g - 2.0 * g * cos_psi;
  return (1.0 - g * g) / (4.0 * std::numbers::pi * denominator * std::sqrt(denominator));
}

WaterBackscatterTable::WaterBackscatterTable(const WaterBackscatterConfig& config,
                                             const BackscatterLamps& lamps,
                                             const std::vector<Eigen::Vector3d>& rays_X,
                                             const BackscatterSpectrum& spectrum)
    : near_(config.near_m),
      span_(config.max_range_m - config.near_m),
      steps_(config.steps),
      channels_(int(spectrum.weight.rows())),
      rays_(int(rays_X.size())) {
  const int wavelengths = int(spectrum.attenuation_per_m.size());
  const std::size_t per_ray = std::size_t(steps_ + 1) * channels_;
  cumulative_.assign(per_ray * rays_, 0.0f);
  tbb::parallel_for(0, rays_, [&](int ray) {
    const Eigen::Vector3d& d = rays_X[std::size_t(ray)];
    std::vector<double> transmitted(wavelengths);  // sum_l w_l exp(-c (r_l + s)) per wavelength
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(channels_);
    float* out = cumulative_.data() + per_ray * std::size_t(ray);
    for (int k = 0; k < steps_; ++k) {
      const double s0 = near_ + span_ * std::pow(double(k) / steps_, 2);
      const double s1 = near_ + span_ * std::pow(double(k + 1) / steps_, 2);
      const double s = 0.5 * (s0 + s1);
      const Eigen::Vector3d x = s * d;
      std::fill(transmitted.begin(), transmitted.end(), 0.0);
      for (std::size_t l = 0; l < lamps.p_X.size(); ++l) {
        const Eigen::Vector3d v = x - lamps.p_X[l];
        const double r = v.norm();
        if (r < 1e-6) continue;
        const double cos_beam = lamps.axis_X[l].dot(v) / r;
        if (cos_beam <= 0.0) continue;
        const double cos_psi = -d.dot(v) / r;
        const double w = lamps.power * std::pow(cos_beam, lamps.beam_exponent) / (r * r) *
                         henyeyGreenstein(cos_psi, config.phase_g);
        for (int i = 0; i < wavelengths; ++i) {
          transmitted[std::size_t(i)] += w * std::exp(-spectrum.attenuation_per_m[std::size_t(i)] * (r + s));
        }
      }
      sum += (s1 - s0) * (spectrum.weight * Eigen::Map<const Eigen::VectorXd>(transmitted.data(), wavelengths));
      for (int c = 0; c < channels_; ++c) out[std::size_t(k + 1) * channels_ + c] = float(sum[c]);
    }
  });
}

WaterBackscatterTable::RangeIndex WaterBackscatterTable::rangeIndex(double range_m) const {
  // The inverse of s = near + span (k / steps)^2.
  const double fraction = std::clamp((range_m - near_) / span_, 0.0, 1.0);
  const double position = steps_ * std::sqrt(fraction);
  const int k = std::min(int(position), steps_ - 1);
  const double s0 = near_ + span_ * std::pow(double(k) / steps_, 2);
  const double s1 = near_ + span_ * std::pow(double(k + 1) / steps_, 2);
  return RangeIndex{k, float(std::clamp((range_m - s0) / (s1 - s0), 0.0, 1.0))};
}

void WaterBackscatterTable::accumulate(int ray, RangeIndex range, float weight, float* out) const {
  const float t = range.t;
  const float* f0 = cumulative_.data() + (std::size_t(ray) * (steps_ + 1) + range.step) * channels_;
  const float* f1 = f0 + channels_;
  for (int c = 0; c < channels_; ++c) out[c] += weight * ((1.0f - t) * f0[c] + t * f1[c]);
}

}  // namespace hsmap
