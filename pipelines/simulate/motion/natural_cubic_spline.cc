#include "pipelines/simulate/motion/natural_cubic_spline.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace hsmap {

NaturalCubicSpline::NaturalCubicSpline(std::vector<double> x, std::vector<double> y)
    : x_(std::move(x)), y_(std::move(y)) {
  if (x_.size() != y_.size() || x_.size() < 2) {
    throw std::invalid_argument(
        "NaturalCubicSpline: expected as many values as knots, at least 2, got " +
        std::to_string(x_.size()) + " knots and " + std::to_string(y_.size()) + " values");
  }
  for (std::size_t i = 0; i < x_.size(); ++i) {
    if (!std::isfinite(x_[i]) || !std::isfinite(y_[i])) {
      throw std::invalid_argument("NaturalCubicSpline: knots and values must be finite");
    }
    if (i > 0 && !(x_[i] > x_[i - 1])) {
      throw std::invalid_argument("NaturalCubicSpline: knots must be strictly increasing");
    }
  }
  const std::size_t n = x_.size() - 1;  // number of intervals
  m_.assign(n + 1, 0.0);
  if (n < 2) return;  // two knots: a straight line

  // Thomas algorithm on the inner unknowns M_1 .. M_{n-1}: forward
  // elimination stores the modified super-diagonal in c and right side in d.
  std::vector<double> c(n, 0.0);
  std::vector<double> d(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const double h_left = x_[i] - x_[i - 1];
    const double h_right = x_[i + 1] - x_[i];
    const double rhs =
        6.0 * ((y_[i + 1] - y_[i]) / h_right - (y_[i] - y_[i - 1]) / h_left);
    const double diagonal = 2.0 * (h_left + h_right) - h_left * c[i - 1];
    c[i] = h_right / diagonal;
    d[i] = (rhs - h_left * d[i - 1]) / diagonal;
  }
  for (std::size_t i = n - 1; i >= 1; --i) m_[i] = d[i] - c[i] * m_[i + 1];
}

std::size_t NaturalCubicSpline::interval(double x) const {
  // upper_bound finds the first knot > x; the interval starts one before it.
  const auto above = std::upper_bound(x_.begin(), x_.end(), x);
  const std::size_t index = above == x_.begin() ? 0 : static_cast<std::size_t>(above - x_.begin()) - 1;
  return std::min(index, x_.size() - 2);
}

double NaturalCubicSpline::value(double x) const {
  if (x < x_.front()) return y_.front() + derivative(x_.front()) * (x - x_.front());
  if (x > x_.back()) return y_.back() + derivative(x_.back()) * (x - x_.back());
  const std::size_t i = interval(x);
  const double h = x_[i + 1] - x_[i];
  const double a = (x_[i + 1] - x) / h;
  const double b = 1.0 - a;
  return a * y_[i] + b * y_[i + 1] +
         ((a * a * a - a) * m_[i] + (b * b * b - b) * m_[i + 1]) * (h * h / 6.0);
}

double NaturalCubicSpline::derivative(double x) const {
  const double clamped = std::clamp(x, x_.front(), x_.back());
  const std::size_t i = interval(clamped);
  const double h = x_[i + 1] - x_[i];
  const double a = (x_[i + 1] - clamped) / h;
  const double b = 1.0 - a;
  return (y_[i + 1] - y_[i]) / h +
         ((1.0 - 3.0 * a * a) * m_[i] + (3.0 * b * b - 1.0) * m_[i + 1]) * (h / 6.0);
}

double NaturalCubicSpline::secondDerivative(double x) const {
  if (x < x_.front() || x > x_.back()) return 0.0;
  const std::size_t i = interval(x);
  const double h = x_[i + 1] - x_[i];
  const double a = (x_[i + 1] - x) / h;
  return a * m_[i] + (1.0 - a) * m_[i + 1];
}

}  // namespace hsmap
