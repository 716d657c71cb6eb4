#include "pipelines/simulate/uhi_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/geometry/pushbroom_camera.h"
#include "pipelines/simulate/sensor_noise.h"

namespace hsmap {

std::vector<double> uhiBandCentres(const SimulatedUhiConfig& config) {
  std::vector<double> centres(config.bands);
  for (int b = 0; b < config.bands; ++b) {
    centres[b] = config.bands == 1 ? config.wavelength_min_nm
                                   : config.wavelength_min_nm + (config.wavelength_max_nm -
                                                                 config.wavelength_min_nm) *
                                                                    b / (config.bands - 1);
  }
  return centres;
}

UhiRenderer::UhiRenderer(const RenderContext& context, const SimulatedUhiConfig& config,
                         std::vector<double> wavelengths_nm, std::uint64_t seed)
    : context_(context), config_(config), wavelengths_nm_(std::move(wavelengths_nm)), seed_(seed) {
  const int bands = static_cast<int>(wavelengths_nm_.size());
  attenuation_.resize(bands);
  lamp_.resize(bands);
  for (int b = 0; b < bands; ++b) {
    attenuation_[b] = float(waterAttenuationPerM(wavelengths_nm_[b], context.turbidity));
    lamp_[b] = float(lampSpectrum(wavelengths_nm_[b]));
  }
  endmembers_ = MaterialField::endmemberMatrix(wavelengths_nm_);

  const PushbroomCamera camera(config.camera);
  const int n = config.subsamples;
  rays_per_pixel_ = n * n;
  const double ifov = config.ifov_across_deg > 0.0 ? config.ifov_across_deg * M_PI / 180.0
                                                   : 1.0 / config.camera.f;
  auto rayThrough = [&](double u, double across_rad) {
    const auto ray = camera.unproject(u);
    if (!ray) {
      throw std::invalid_argument("uhi.camera.distortion: pixel " + std::to_string(u) +
                                  " has no ray (the distortion folds over inside the line)");
    }
    return Eigen::Vector3d(ray->x() / ray->z(), std::tan(across_rad), 1.0).normalized();
  };
  for (int s = 0; s < config.camera.samples; ++s) {
    centre_rays_U_.push_back(rayThrough(s, 0.0));
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        rays_U_.push_back(rayThrough(s + (i + 0.5) / n - 0.5, ifov * ((j + 0.5) / n - 0.5)));
      }
    }
  }

  // Exposure: a flat surface below the camera at the nominal altitude.
  const double altitude = context.nominal_altitude_m;
  const LampLighting lighting = context.lamps->nominalLighting(altitude);
  Eigen::ArrayXf radiance = Eigen::ArrayXf::Zero(bands);
  for (int l = 0; l < lighting.count; ++l) {
    radiance += float(lighting.weight[l]) *
                (-attenuation_ * float(lighting.path_length[l] + altitude)).exp() * lamp_;
  }
  const double brightest = radiance.maxCoeff() / M_PI * config.exposure_reflectance;
  if (!(brightest > 0.0)) {
    throw std::invalid_argument("optics: the lamps do not light the seabed below the UHI");
  }
  gain_ = 60000.0 / brightest;

  if (context.backscatter.enabled) {
    grid_ = (config.camera.samples + kBackscatterGridSamples - 1) / kBackscatterGridSamples + 1;
    std::vector<Eigen::Vector3d> grid_rays_U;
    for (int i = 0; i < grid_; ++i) {
      grid_rays_U.push_back(rayThrough(-0.5 + double(i) * config.camera.samples / (grid_ - 1), 0.0));
    }
    // Per band: pi I_b b_b, so that gain_ / pi times the table is the DN.
    BackscatterSpectrum spectrum;
    spectrum.weight = Eigen::MatrixXd::Zero(bands, bands);
    for (int b = 0; b < bands; ++b) {
      spectrum.attenuation_per_m.push_back(double(attenuation_[b]));
      spectrum.weight(b, b) =
          M_PI * double(lamp_[b]) * waterScatteringPerM(wavelengths_nm_[std::size_t(b)], context.turbidity);
    }
    backscatter_ = std::make_unique<WaterBackscatterTable>(
        context.backscatter, context.lamps->backscatterLamps(context.T_B_C * context.T_C_U),
        grid_rays_U, spectrum);
  }
}

void UhiRenderer::addBackscatter(double u, double range_m, float weight, float* out) const {
  const double f = (u + 0.5) * (grid_ - 1) / config_.camera.samples;
  const int i = std::clamp(int(std::floor(f)), 0, grid_ - 2);
  const float t = float(std::clamp(f - i, 0.0, 1.0));
  const WaterBackscatterTable::RangeIndex range = backscatter_->rangeIndex(range_m);
  backscatter_->accumulate(i, range, weight * (1.0f - t), out);
  backscatter_->accumulate(i + 1, range, weight * t, out);
}

Eigen::VectorXf UhiRenderer::backscatterDn(double u, double range_m) const {
  Eigen::VectorXf dn = Eigen::VectorXf::Zero(Eigen::Index(wavelengths_nm_.size()));
  if (backscatter_) addBackscatter(u, range_m, float(gain_ / M_PI), dn.data());
  return dn;
}

std::vector<double> UhiRenderer::nominalBackscatterDn() const {
  if (!backscatter_) return {};
  // The body level (T_W_B = identity): the seabed plane z_B = z of the RGB
  // camera + altitude; the principal ray from the UHI's centre to it.
  const SE3d T_B_U = context_.T_B_C * context_.T_C_U;
  const Eigen::Vector3d ray_B = T_B_U.q * Eigen::Vector3d(0.0, 0.0, 1.0);
  const double seabed_z_B = context_.T_B_C.t.z() + context_.nominal_altitude_m;
  const double range = (seabed_z_B - T_B_U.t.z()) / ray_B.z();
  const Eigen::VectorXf dn = backscatterDn(config_.camera.cx, range);
  return std::vector<double>(dn.data(), dn.data() + dn.size());
}

std::vector<double> UhiRenderer::lampResponseDn() const {
  std::vector<double> dn(wavelengths_nm_.size());
  // The same float arithmetic as render(): lamp_ * float(gain_ / pi) * weight.
  const float scale = float(gain_ / M_PI);
  for (std::size_t b = 0; b < dn.size(); ++b) {
    dn[b] = double(lamp_[Eigen::Index(b)] * scale * float(context_.lamps->power()));
  }
  return dn;
}

void UhiRenderer::render(const SE3d& T_W_B, const SE3d& T_W_U, std::int64_t line_index,
                         UhiLineImage& out) const {
  const int samples = config_.camera.samples;
  const int bands = static_cast<int>(wavelengths_nm_.size());
  out.dn.resize(bands, samples);
  out.centre_hits_W.assign(samples, Eigen::Vector3d::Constant(
                                        std::numeric_limits<double>::quiet_NaN()));
  const Eigen::Matrix3d R_W_U = T_W_U.q.toRotationMatrix();
  const LampRig::Posed lamps = context_.lamps->posed(T_W_B);
  constexpr int kChunk = 64;
  const int chunks = (samples + kChunk - 1) / kChunk;
  tbb::parallel_for(0, chunks, [&](int chunk) {
    const int s_begin = chunk * kChunk;
    const int s_end = std::min(samples, s_begin + kChunk);
    const int count = s_end - s_begin;
    std::vector<Ray> rays(std::size_t(count) * (rays_per_pixel_ + 1));
    std::vector<RayHit> hits(rays.size());
    for (int s = s_begin; s < s_end; ++s) {
      const std::size_t base = std::size_t(s - s_begin) * (rays_per_pixel_ + 1);
      for (int r = 0; r < rays_per_pixel_; ++r) {
        rays[base + r].origin = T_W_U.t;
        rays[base + r].direction = R_W_U * rays_U_[std::size_t(s) * rays_per_pixel_ + r];
      }
      rays[base + rays_per_pixel_].origin = T_W_U.t;
      rays[base + rays_per_pixel_].direction = R_W_U * centre_rays_U_[s];
    }
    context_.caster->intersect(rays, hits);
    SensorNoise noise(noiseSeed(seed_, 2, std::uint64_t(line_index) * 1024 + chunk));
    Eigen::ArrayXf radiance(bands);
    for (int s = s_begin; s < s_end; ++s) {
      const std::size_t base = std::size_t(s - s_begin) * (rays_per_pixel_ + 1);
      std::array<Eigen::Matrix<float, kEndmemberCount, 1>, LampLighting::kMaxLamps> w;
      std::array<double, LampLighting::kMaxLamps> path_sum{};
      std::array<double, LampLighting::kMaxLamps> path_weight{};
      for (auto& wl : w) wl.setZero();
      for (int r = 0; r < rays_per_pixel_; ++r) {
        const RayHit& hit = hits[base + r];
        if (!hit.hit()) continue;
        const Ray& ray = rays[base + r];
        const Eigen::Vector3d p_W = ray.origin + hit.distance * ray.direction;
        const Abundances a = context_.materials->abundances(p_W, context_.kindOf(hit.triangle));
        const Eigen::Map<const Eigen::Matrix<float, kEndmemberCount, 1>> a_vec(a.data());
        const LampLighting lighting =
            context_.lamps->light(lamps, p_W, hit.normal, context_.shadowCaster());
        for (int l = 0; l < lighting.count; ++l) {
          if (lighting.weight[l] <= 0.0) continue;
          w[l] += float(lighting.weight[l]) * a_vec;
          path_sum[l] += lighting.weight[l] * (lighting.path_length[l] + hit.distance);
          path_weight[l] += lighting.weight[l];
        }
      }
      radiance.setZero();
      for (int l = 0; l < LampLighting::kMaxLamps; ++l) {
        if (path_weight[l] <= 0.0) continue;
        const float mean_path = float(path_sum[l] / path_weight[l]);
        radiance += (endmembers_ * w[l]).array() * (-attenuation_ * mean_path).exp();
      }
      radiance *= lamp_ * float(gain_ / (M_PI * rays_per_pixel_));
      if (backscatter_) {
        // At the mean range of the rays that hit; the others see the water
        // column to the maximum range.
        double range_sum = 0.0;
        int hit_count = 0;
        for (int r = 0; r < rays_per_pixel_; ++r) {
          if (!hits[base + r].hit()) continue;
          range_sum += hits[base + r].distance;
          ++hit_count;
        }
        const float scale = float(gain_ / M_PI) / float(rays_per_pixel_);
        if (hit_count > 0) addBackscatter(s, range_sum / hit_count, scale * float(hit_count), radiance.data());
        if (hit_count < rays_per_pixel_) {
          addBackscatter(s, backscatter_->maxRange(), scale * float(rays_per_pixel_ - hit_count),
                         radiance.data());
        }
      }
      for (int b = 0; b < bands; ++b) {
        const float dn = radiance[b];
        const float sigma = std::sqrt(float(config_.read_noise_dn * config_.read_noise_dn) +
                                      std::max(dn, 0.0f) / float(config_.electrons_per_dn));
        out.dn(b, s) = std::clamp(dn + sigma * float(noise.normal()), 0.0f, 65535.0f);
      }
      const RayHit& centre = hits[base + rays_per_pixel_];
      if (centre.hit()) {
        const Ray& ray = rays[base + rays_per_pixel_];
        out.centre_hits_W[s] = ray.origin + centre.distance * ray.direction;
      }
    }
  });
}

}  // namespace hsmap
