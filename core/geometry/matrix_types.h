#pragma once
// Fixed-size Eigen types templated on the scalar, so that the geometry code
// can be instantiated with double and with ceres::Jet<double, N> (autodiff)
// alike. Only aliases: no behaviour lives here.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hsmap {

template <class T>
using Vector2 = Eigen::Matrix<T, 2, 1>;
template <class T>
using Vector3 = Eigen::Matrix<T, 3, 1>;
template <class T>
using Vector6 = Eigen::Matrix<T, 6, 1>;
template <class T>
using Matrix3 = Eigen::Matrix<T, 3, 3>;
template <class T>
using Matrix4 = Eigen::Matrix<T, 4, 4>;
template <class T>
using Matrix6 = Eigen::Matrix<T, 6, 6>;

using Vector6d = Vector6<double>;
using Matrix6d = Matrix6<double>;

}  // namespace hsmap
