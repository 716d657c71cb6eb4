#pragma once
// Central-difference Jacobian for the geometry tests: J(:, k) =
// (f(x + h e_k) - f(x - h e_k)) / (2 h). Truncation error is O(h^2 f'''),
// rounding error O(eps |f| / h); h = 1e-6 balances both near 1e-10 for the
// well-scaled functions tested here.

#include <Eigen/Core>
#include <functional>

namespace hsmap::test {

inline Eigen::MatrixXd numericJacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
    double h = 1e-6) {
  const Eigen::VectorXd f0 = f(x);
  Eigen::MatrixXd J(f0.size(), x.size());
  for (int k = 0; k < x.size(); ++k) {
    Eigen::VectorXd plus = x, minus = x;
    plus(k) += h;
    minus(k) -= h;
    J.col(k) = (f(plus) - f(minus)) / (2.0 * h);
  }
  return J;
}

}  // namespace hsmap::test
