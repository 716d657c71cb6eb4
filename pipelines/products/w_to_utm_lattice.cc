#include "pipelines/products/w_to_utm_lattice.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hsmap {

WToUtmLattice::WToUtmLattice(const UtmProjection& projection, const Eigen::AlignedBox2d& bounds_NE,
                             double down_m, double min_spacing_m, int max_nodes_per_side)
    : projection_(projection), down_m_(down_m) {
  if (bounds_NE.isEmpty() || !bounds_NE.min().allFinite() || !bounds_NE.max().allFinite() ||
      !std::isfinite(down_m)) {
    throw std::invalid_argument("WToUtmLattice: empty or non-finite bounds");
  }
  if (!(min_spacing_m > 0.0) || max_nodes_per_side < 2) {
    throw std::invalid_argument("WToUtmLattice: min_spacing_m must be > 0 and max_nodes_per_side >= 2");
  }
  const Eigen::Vector2d size = bounds_NE.sizes();
  spacing_ = std::max(min_spacing_m, size.maxCoeff() / double(max_nodes_per_side - 3));
  north0_ = bounds_NE.min().x() - spacing_;
  east0_ = bounds_NE.min().y() - spacing_;
  n_rows_ = int(std::ceil(size.x() / spacing_)) + 3;
  n_cols_ = int(std::ceil(size.y() / spacing_)) + 3;
  nodes_.resize(std::size_t(n_rows_) * n_cols_);
  per_down_.resize(nodes_.size());
  for (int i = 0; i < n_rows_; ++i) {
    for (int j = 0; j < n_cols_; ++j) {
      const Eigen::Vector3d p(north0_ + i * spacing_, east0_ + j * spacing_, down_m_);
      const std::size_t k = std::size_t(i) * n_cols_ + j;
      nodes_[k] = projection_.nedToUtm(p);
      per_down_[k] = projection_.nedToUtm(p + Eigen::Vector3d(0.0, 0.0, 1.0)) - nodes_[k];
    }
  }
}

Eigen::Vector2d WToUtmLattice::toUtm(const Eigen::Vector3d& p_W) const {
  const double x = (p_W.x() - north0_) / spacing_;
  const double y = (p_W.y() - east0_) / spacing_;
  if (!(x >= 0.0 && y >= 0.0 && x < n_rows_ - 1 && y < n_cols_ - 1) || !std::isfinite(p_W.z())) {
    return projection_.nedToUtm(p_W);
  }
  const int i = int(x), j = int(y);
  const double a = x - i, b = y - j;
  const std::size_t k = std::size_t(i) * n_cols_ + j;
  auto bilinear = [&](const std::vector<Eigen::Vector2d>& v) {
    return (1 - a) * ((1 - b) * v[k] + b * v[k + 1]) + a * ((1 - b) * v[k + n_cols_] + b * v[k + n_cols_ + 1]);
  };
  return bilinear(nodes_) + (p_W.z() - down_m_) * bilinear(per_down_);
}

}  // namespace hsmap
