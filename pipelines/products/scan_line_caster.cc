#include "pipelines/products/scan_line_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "core/raycast/ray.h"

namespace hsmap {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
}  // namespace

void ScanLineCastOptions::validate() const {
  if (!(min_range_m >= 0.0) || !std::isfinite(min_range_m)) {
    throw std::invalid_argument("min_range_m: expected a finite number >= 0, got " +
                                std::to_string(min_range_m));
  }
  if (!(max_range_m > min_range_m)) {
    throw std::invalid_argument("max_range_m: expected a number > min_range_m, got " +
                                std::to_string(max_range_m));
  }
}

ScanLineCaster::ScanLineCaster(const PushbroomCamera& camera, const MeshRayCaster& mesh,
                               const ScanLineCastOptions& options)
    : camera_(camera), mesh_(mesh), options_(options) {
  options_.validate();
  rays_U_.resize(std::size_t(camera.samples()));
  for (int s = 0; s < camera.samples(); ++s) {
    const auto ray = camera.unproject(double(s));
    if (ray) {
      rays_U_[std::size_t(s)] = ray->normalized();
      ++samples_with_ray_;
    } else {
      rays_U_[std::size_t(s)] = Eigen::Vector3d::Constant(kNaN);
    }
  }
}

void ScanLineCaster::castLine(std::int64_t line, const SE3d& T_W_U, ScanLineHits& out) const {
  const int samples = camera_.samples();
  out.line = line;
  out.p_W.assign(std::size_t(samples), Eigen::Vector3d::Constant(kNaN));
  out.range_m.assign(std::size_t(samples), kNaNf);
  out.incidence_deg.assign(std::size_t(samples), kNaNf);
  out.triangle.assign(std::size_t(samples), -1);
  out.hits = out.misses = 0;
  out.no_ray = samples - samples_with_ray_;

  // Rays of the pixels that have one, in sample order (a coherent batch).
  thread_local std::vector<Ray> rays;
  thread_local std::vector<RayHit> hits;
  thread_local std::vector<int> sample_of;
  rays.clear();
  sample_of.clear();
  const Eigen::Matrix3d R_W_U = T_W_U.rotationMatrix();
  for (int s = 0; s < samples; ++s) {
    const Eigen::Vector3d& d_U = rays_U_[std::size_t(s)];
    if (!(d_U.z() > 0.0)) continue;  // no ray (NaN)
    Ray ray;
    ray.origin = T_W_U.t;
    ray.direction = R_W_U * d_U;
    ray.t_near = options_.min_range_m;
    ray.t_far = options_.max_range_m;
    rays.push_back(ray);
    sample_of.push_back(s);
  }
  hits.resize(rays.size());
  mesh_.intersect(std::span<const Ray>(rays), std::span<RayHit>(hits));
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const RayHit& hit = hits[i];
    if (!hit.hit()) {
      ++out.misses;
      continue;
    }
    const std::size_t s = std::size_t(sample_of[i]);
    const Ray& ray = rays[i];
    out.p_W[s] = ray.origin + hit.distance * ray.direction;
    out.range_m[s] = float(hit.distance);
    out.triangle[s] = hit.triangle;
    // The normal faces the ray's origin: the incidence is the angle between
    // -direction and the normal.
    const double cosine = std::clamp(-hit.normal.dot(ray.direction), -1.0, 1.0);
    out.incidence_deg[s] = float(std::acos(cosine) * 180.0 / M_PI);
    ++out.hits;
  }
}

void ScanLineCaster::castLines(std::span<const std::int64_t> lines, std::span<const SE3d> T_W_U,
                               std::vector<ScanLineHits>& out) const {
  if (lines.size() != T_W_U.size()) {
    throw std::invalid_argument("ScanLineCaster::castLines: " + std::to_string(lines.size()) +
                                " lines but " + std::to_string(T_W_U.size()) + " poses");
  }
  out.resize(lines.size());
  tbb::parallel_for(std::size_t(0), lines.size(),
                    [&](std::size_t i) { castLine(lines[i], T_W_U[i], out[i]); });
}

}  // namespace hsmap
