#include "pipelines/simulate/rgb_renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "core/geometry/pinhole_radtan_camera.h"
#include "pipelines/simulate/sensor_noise.h"

namespace hsmap {
namespace {

std::vector<Eigen::Vector2d> subPixelOffsets(int samples_per_pixel) {
  switch (samples_per_pixel) {
    case 4:  // rotated grid: no two samples share a row or a column
      return {{-0.125, -0.375}, {0.375, -0.125}, {0.125, 0.375}, {-0.375, 0.125}};
    default:  // 1, and the centre of quincunx (2)
      return {{0.0, 0.0}};
  }
}

Eigen::Vector3d rayThrough(const PinholeRadtanCamera& camera, double u, double v) {
  const auto ray = camera.unproject(Eigen::Vector2d(u, v));
  if (!ray) {
    throw std::invalid_argument("rgb.camera.distortion: image point (" + std::to_string(u) + ", " +
                                std::to_string(v) +
                                ") has no ray (the distortion folds over inside the image)");
  }
  return ray->normalized();
}

}  // namespace

RgbRenderer::RgbRenderer(const RenderContext& context, const SimulatedRgbConfig& config,
                         std::uint64_t seed)
    : context_(context), config_(config), seed_(seed), table_(context.turbidity) {
  const PinholeRadtanCamera camera(config.camera);
  const auto offsets = subPixelOffsets(config.samples_per_pixel);
  rays_C_.reserve(std::size_t(camera.width()) * camera.height() * offsets.size());
  for (int v = 0; v < camera.height(); ++v) {
    for (int u = 0; u < camera.width(); ++u) {
      for (const Eigen::Vector2d& offset : offsets) {
        rays_C_.push_back(rayThrough(camera, u + offset.x(), v + offset.y()));
      }
    }
  }
  if (config.samples_per_pixel == 2) {
    for (int v = 0; v <= camera.height(); ++v) {
      for (int u = 0; u <= camera.width(); ++u) {
        corner_rays_C_.push_back(rayThrough(camera, u - 0.5, v - 0.5));
      }
    }
  }
  vignetting_ = vignettingImage(config.vignetting, config.camera);
  if (context.backscatter.enabled) {
    for (int v = 0; v < camera.height(); ++v) {
      for (int u = 0; u < camera.width(); ++u) {
        for (const Eigen::Vector2d& offset : offsets) {
          uv_.emplace_back(float(u + offset.x()), float(v + offset.y()));
        }
      }
    }
    if (config.samples_per_pixel == 2) {
      for (int v = 0; v <= camera.height(); ++v) {
        for (int u = 0; u <= camera.width(); ++u) corner_uv_.emplace_back(u - 0.5f, v - 0.5f);
      }
    }
    grid_u_ = (camera.width() + kBackscatterGridPx - 1) / kBackscatterGridPx + 1;
    grid_v_ = (camera.height() + kBackscatterGridPx - 1) / kBackscatterGridPx + 1;
    std::vector<Eigen::Vector3d> grid_rays_C;
    for (int j = 0; j < grid_v_; ++j) {
      for (int i = 0; i < grid_u_; ++i) {
        grid_rays_C.push_back(rayThrough(camera, -0.5 + double(i) * camera.width() / (grid_u_ - 1),
                                         -0.5 + double(j) * camera.height() / (grid_v_ - 1)));
      }
    }
    // The channels as the radiance table integrates them (rgb_radiance_table.h),
    // times pi: the renderer's linear value is pi times the radiance.
    std::vector<double> wavelengths;
    for (double nm = 380.0; nm <= 720.0; nm += 5.0) wavelengths.push_back(nm);
    BackscatterSpectrum spectrum;
    spectrum.weight.resize(3, Eigen::Index(wavelengths.size()));
    for (std::size_t i = 0; i < wavelengths.size(); ++i) {
      const double nm = wavelengths[i];
      spectrum.attenuation_per_m.push_back(waterAttenuationPerM(nm, context.turbidity));
      for (int k = 0; k < 3; ++k) {
        spectrum.weight(k, Eigen::Index(i)) = M_PI * rgbResponse(k, nm) * lampSpectrum(nm) *
                                              waterScatteringPerM(nm, context.turbidity) * 5.0;
      }
    }
    backscatter_ = std::make_unique<WaterBackscatterTable>(
        context.backscatter, context.lamps->backscatterLamps(context.T_B_C), grid_rays_C, spectrum);
  }
  // Exposure: a flat surface below the camera at the nominal altitude.
  const double altitude = context.nominal_altitude_m;
  const LampLighting lighting = context.lamps->nominalLighting(altitude);
  Eigen::Vector3f rgb = Eigen::Vector3f::Zero();
  for (int l = 0; l < lighting.count; ++l) {
    rgb += float(lighting.weight[l]) * table_.at(lighting.path_length[l] + altitude).col(kEndmemberCount);
  }
  const double brightest = rgb.maxCoeff() / M_PI * config.exposure_reflectance;
  if (!(brightest > 0.0)) {
    throw std::invalid_argument("optics: the lamps do not light the seabed below the RGB camera");
  }
  gain_ = 250.0 / brightest;
}

Eigen::Vector3f RgbRenderer::shade(const Eigen::Vector3d& p_W, const RayHit& hit,
                                   const LampLighting& lighting) const {
  Eigen::Vector3f linear = Eigen::Vector3f::Zero();
  const Abundances a = context_.materials->abundances(p_W, context_.kindOf(hit.triangle));
  const Eigen::Map<const Eigen::Matrix<float, kEndmemberCount, 1>> a_vec(a.data());
  for (int l = 0; l < lighting.count; ++l) {
    if (lighting.weight[l] <= 0.0) continue;
    const auto entry = table_.at(lighting.path_length[l] + hit.distance);
    linear += float(lighting.weight[l]) * (entry.leftCols<kEndmemberCount>() * a_vec);
  }
  return linear;
}

void RgbRenderer::drawMarineSnow(const std::vector<SnowParticle>& particles, const Pose& pose,
                                 std::vector<Eigen::Vector3f>& linear) const {
  const MarineSnowConfig& snow = context_.marine_snow;
  const PinholeRadtanCamera camera(config_.camera);
  const int width = config_.camera.width;
  const int height = config_.camera.height;
  const double f = config_.camera.fx;
  const SE3d T_C_W = pose.T_W_C.inverse();
  const LampRig::Posed lamps = context_.lamps->posed(pose.T_W_B);
  const double power = context_.lamps->power();
  const double beam_exponent = context_.lamps->beamExponent();
  for (const SnowParticle& particle : particles) {
    const Eigen::Vector3d p_C = T_C_W * particle.p_W;
    const double z = p_C.z();
    if (z <= 0.01) continue;
    const double d = p_C.norm();
    const Eigen::Vector3d to_particle = (particle.p_W - pose.T_W_C.t) / d;
    if (context_.caster->occluded(Ray{pose.T_W_C.t, to_particle, 0.0, d})) continue;
    Eigen::Vector3f value = Eigen::Vector3f::Zero();
    for (int l = 0; l < LampLighting::kMaxLamps; ++l) {
      const Eigen::Vector3d from_lamp = particle.p_W - lamps.lamp_W[l];
      const double r = from_lamp.norm();
      const double cos_beam = lamps.axis_W.dot(from_lamp) / r;
      if (cos_beam <= 0.0) continue;
      const double g = power * std::pow(cos_beam, beam_exponent) / (r * r);
      value += float(g) * table_.at(r + d).col(kEndmemberCount);
    }
    const Eigen::Vector2d uv = camera.project(p_C);
    const double radius = f * particle.diameter_m / (2.0 * z);
    const double blur = snow.aperture_mm * 1e-3 * f * std::abs(1.0 / z - 1.0 / context_.nominal_altitude_m);
    const double sigma = std::sqrt(0.25 * radius * radius + blur * blur / 16.0 + 0.09);
    value *= float(snow.albedo * M_PI * radius * radius);
    const int reach = int(std::ceil(3.0 * sigma));
    const int u0 = std::max(0, int(std::floor(uv.x())) - reach);
    const int u1 = std::min(width - 1, int(std::ceil(uv.x())) + reach);
    const int v0 = std::max(0, int(std::floor(uv.y())) - reach);
    const int v1 = std::min(height - 1, int(std::ceil(uv.y())) + reach);
    if (u0 > u1 || v0 > v1) continue;
    // The dot's weights sum to 1 over its whole window (also when sigma is
    // below a pixel), so the particle adds exactly its value times its area.
    double total = 0.0;
    for (int v = int(std::floor(uv.y())) - reach; v <= int(std::ceil(uv.y())) + reach; ++v) {
      for (int u = int(std::floor(uv.x())) - reach; u <= int(std::ceil(uv.x())) + reach; ++u) {
        total += std::exp(-(std::pow(u - uv.x(), 2) + std::pow(v - uv.y(), 2)) / (2.0 * sigma * sigma));
      }
    }
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        const double w = std::exp(-(std::pow(u - uv.x(), 2) + std::pow(v - uv.y(), 2)) / (2.0 * sigma * sigma));
        linear[std::size_t(v) * width + u] += float(w / total) * value;
      }
    }
  }
}

void RgbRenderer::addBackscatter(const Eigen::Vector2f& uv, double range_m,
                                 Eigen::Vector3f& linear) const {
  const float fu = (uv.x() + 0.5f) * float(grid_u_ - 1) / float(config_.camera.width);
  const float fv = (uv.y() + 0.5f) * float(grid_v_ - 1) / float(config_.camera.height);
  const int i = std::clamp(int(std::floor(fu)), 0, grid_u_ - 2);
  const int j = std::clamp(int(std::floor(fv)), 0, grid_v_ - 2);
  const float tu = std::clamp(fu - float(i), 0.0f, 1.0f);
  const float tv = std::clamp(fv - float(j), 0.0f, 1.0f);
  const int ray = j * grid_u_ + i;
  const WaterBackscatterTable::RangeIndex range = backscatter_->rangeIndex(range_m);
  backscatter_->accumulate(ray, range, (1.0f - tu) * (1.0f - tv), linear.data());
  backscatter_->accumulate(ray + 1, range, tu * (1.0f - tv), linear.data());
  backscatter_->accumulate(ray + grid_u_, range, (1.0f - tu) * tv, linear.data());
  backscatter_->accumulate(ray + grid_u_ + 1, range, tu * tv, linear.data());
}

void RgbRenderer::shadeRays(const SE3d& T_W_B, const SE3d& T_W_C, const Eigen::Vector3d* rays_C,
                            const Eigen::Vector2f* uv, int count, Eigen::Vector3f* out) const {
  // Per thread, reused across rows and frames: the renderer allocates nothing per row.
  struct Buffers {
    std::vector<Ray> rays;
    std::vector<RayHit> hits;
    std::vector<Eigen::Vector3d> points_W;
    std::vector<LampLighting> lighting;
    std::vector<Ray> shadow_rays;
    std::vector<std::pair<int, int>> shadow_of;  // (ray, lamp) of each shadow ray
    std::vector<std::uint8_t> occluded;
  };
  thread_local Buffers buffers;
  Buffers& b = buffers;
  b.rays.resize(count);
  b.hits.resize(count);
  b.points_W.resize(count);
  b.lighting.resize(count);
  b.shadow_rays.clear();
  b.shadow_of.clear();
  const Eigen::Matrix3d R_W_C = T_W_C.q.toRotationMatrix();
  for (int i = 0; i < count; ++i) {
    b.rays[i].origin = T_W_C.t;
    b.rays[i].direction = R_W_C * rays_C[i];
  }
  context_.caster->intersect(std::span<const Ray>(b.rays.data(), count),
                             std::span<RayHit>(b.hits.data(), count));
  std::array<Ray, LampLighting::kMaxLamps> shadow_rays;
  const LampRig::Posed lamps = context_.lamps->posed(T_W_B);
  for (int i = 0; i < count; ++i) {
    if (!b.hits[i].hit()) continue;
    b.points_W[i] = b.rays[i].origin + b.hits[i].distance * b.rays[i].direction;
    b.lighting[i] =
        context_.lamps->lightUnshadowed(lamps, b.points_W[i], b.hits[i].normal, &shadow_rays);
    if (!context_.shadows) continue;
    for (int l = 0; l < b.lighting[i].count; ++l) {
      if (b.lighting[i].weight[l] <= 0.0) continue;
      b.shadow_rays.push_back(shadow_rays[l]);
      b.shadow_of.emplace_back(i, l);
    }
  }
  // All shadow rays of the row in one batch: rays towards one lamp from
  // neighbouring points travel together through the BVH.
  b.occluded.resize(b.shadow_rays.size());
  context_.caster->occluded(b.shadow_rays, b.occluded);
  for (std::size_t k = 0; k < b.shadow_rays.size(); ++k) {
    if (b.occluded[k]) b.lighting[b.shadow_of[k].first].weight[b.shadow_of[k].second] = 0.0;
  }
  for (int i = 0; i < count; ++i) {
    if (!b.hits[i].hit()) {
      out[i].setZero();
    } else {
      out[i] = shade(b.points_W[i], b.hits[i], b.lighting[i]);
    }
    if (backscatter_) {
      addBackscatter(uv[i], b.hits[i].hit() ? b.hits[i].distance : backscatter_->maxRange(), out[i]);
    }
  }
}

void RgbRenderer::renderLinear(const Pose& pose, std::vector<Eigen::Vector3f>& sum,
                               bool accumulate) const {
  const int width = config_.camera.width;
  const int height = config_.camera.height;
  const int per_pixel = config_.samples_per_pixel == 4 ? 4 : 1;
  const bool quincunx = config_.samples_per_pixel == 2;
  // Quincunx: the corners first, each shared by up to four pixels.
  std::vector<Eigen::Vector3f> corners;
  if (quincunx) {
    corners.resize(std::size_t(width + 1) * (height + 1));
    tbb::parallel_for(0, height + 1, [&](int v) {
      const std::size_t offset = std::size_t(v) * (width + 1);
      shadeRays(pose.T_W_B, pose.T_W_C, corner_rays_C_.data() + offset,
                backscatter_ ? corner_uv_.data() + offset : nullptr, width + 1, corners.data() + offset);
    });
  }
  tbb::parallel_for(0, height, [&](int v) {
    const std::size_t row_rays = std::size_t(width) * per_pixel;
    thread_local std::vector<Eigen::Vector3f> samples;
    samples.resize(row_rays);
    shadeRays(pose.T_W_B, pose.T_W_C, rays_C_.data() + std::size_t(v) * row_rays,
              backscatter_ ? uv_.data() + std::size_t(v) * row_rays : nullptr, int(row_rays),
              samples.data());
    Eigen::Vector3f* out = sum.data() + std::size_t(v) * width;
    for (int u = 0; u < width; ++u) {
      Eigen::Vector3f linear = Eigen::Vector3f::Zero();
      if (quincunx) {
        const Eigen::Vector3f* top = corners.data() + std::size_t(v) * (width + 1) + u;
        const Eigen::Vector3f* bottom = top + (width + 1);
        linear = 0.5f * samples[u] + 0.125f * (top[0] + top[1] + bottom[0] + bottom[1]);
      } else {
        for (int s = 0; s < per_pixel; ++s) linear += samples[std::size_t(u) * per_pixel + s];
        linear /= float(per_pixel);
      }
      if (accumulate) {
        out[u] += linear;
      } else {
        out[u] = linear;
      }
    }
  });
}

cv::Mat RgbRenderer::render(const SE3d& T_W_B, const SE3d& T_W_C, std::int64_t frame_index) const {
  const Pose pose{T_W_B, T_W_C};
  return render(std::span<const Pose>(&pose, 1), 1.0, frame_index);
}

cv::Mat RgbRenderer::render(std::span<const Pose> subframes, double gain,
                            std::int64_t frame_index) const {
  if (subframes.empty() || !(gain > 0.0)) {
    throw std::invalid_argument("RgbRenderer::render: expected at least one sub-frame and a gain > 0");
  }
  const int width = config_.camera.width;
  const int height = config_.camera.height;
  std::vector<Eigen::Vector3f> linear_image(std::size_t(width) * height);
  std::vector<SnowParticle> snow;
  if (context_.marine_snow.enabled) {
    snow = sampleMarineSnow(context_.marine_snow, config_.camera, subframes[subframes.size() / 2].T_W_C,
                            noiseSeed(seed_, 3, std::uint64_t(frame_index)));
  }
  for (std::size_t i = 0; i < subframes.size(); ++i) {
    renderLinear(subframes[i], linear_image, i > 0);
    if (!snow.empty()) drawMarineSnow(snow, subframes[i], linear_image);
  }
  // One sub-frame: no division, so that the frame is the instantaneous render bit for bit.
  const float subframe_weight = 1.0f / float(subframes.size());
  const bool average = subframes.size() > 1;
  // gain_ / pi * 1.0 is gain_ / pi exactly: a gain of 1 changes no bit.
  const float scale = float(gain_ / M_PI * gain);
  const double read_noise_dn = config_.read_noise_dn * gain;
  cv::Mat image(height, width, CV_8UC3);
  tbb::parallel_for(0, height, [&](int v) {
    SensorNoise noise(noiseSeed(seed_, 1, std::uint64_t(frame_index) * 65536 + v));
    const Eigen::Vector3f* row = linear_image.data() + std::size_t(v) * width;
    const float* vignetting = vignetting_.empty() ? nullptr : vignetting_.data() + std::size_t(v) * width;
    auto* out = image.ptr<cv::Vec3b>(v);
    for (int u = 0; u < width; ++u) {
      Eigen::Vector3f linear = row[u];
      if (average) linear *= subframe_weight;
      if (vignetting != nullptr) linear *= vignetting[u];
      linear *= scale;
      for (int k = 0; k < 3; ++k) {
        const double dn = linear[k];
        const double sigma = std::sqrt(read_noise_dn * read_noise_dn +
                                       gain * std::max(dn, 0.0) / config_.electrons_per_dn);
        const double noisy = dn + sigma * noise.normal();
        out[u][2 - k] = static_cast<std::uint8_t>(std::clamp(std::lround(noisy), 0L, 255L));
      }
    }
  });
  return image;
}

}  // namespace hsmap
