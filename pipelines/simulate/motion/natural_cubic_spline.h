#pragma once
// NaturalCubicSpline: the interpolating cubic spline through (x_i, y_i) with
// zero second derivative at both ends (de Boor, "A Practical Guide to
// Splines", ch. IV). It is C2: value, slope and curvature are continuous at
// every knot, which is what a trajectory needs so that its velocity and
// acceleration have no jumps.
//
// On [x_i, x_{i+1}], with h = x_{i+1} - x_i, a = (x_{i+1} - x) / h, b = 1 - a
// and M_i the second derivative at knot i:
//   y(x) = a y_i + b y_{i+1} + ((a^3 - a) M_i + (b^3 - b) M_{i+1}) h^2 / 6.
// Continuity of the slope at the inner knots gives the tridiagonal system
//   h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1}
//     = 6 ((y_{i+1} - y_i) / h_i - (y_i - y_{i-1}) / h_{i-1}),  M_0 = M_n = 0,
// solved once in the constructor (Thomas algorithm, O(n); the matrix is
// strictly diagonally dominant, so no pivoting is needed).
//
// Outside [x_0, x_n] the spline continues as the straight line of its end
// slope: with M = 0 at the ends that extension keeps it C2.
// Evaluation is O(log n) (binary search for the interval), allocation-free.

#include <vector>

namespace hsmap {

class NaturalCubicSpline {
 public:
  // Throws std::invalid_argument unless x and y have the same size >= 2, all
  // values are finite and x is strictly increasing.
  NaturalCubicSpline(std::vector<double> x, std::vector<double> y);

  double value(double x) const;
  double derivative(double x) const;
  double secondDerivative(double x) const;

  const std::vector<double>& knots() const { return x_; }

 private:
  // Index i of the interval [x_i, x_{i+1}] holding x (clamped to the end intervals).
  std::size_t interval(double x) const;

  std::vector<double> x_;
  std::vector<double> y_;
  std::vector<double> m_;  // second derivative at each knot
};

}  // namespace hsmap
