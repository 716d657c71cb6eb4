#pragma once
// scalarPart(x): the plain double value of a residual functor's scalar, i.e.
// x itself for double and the value part of a ceres::Jet. A functor uses it
// only for discrete choices that must not be differentiated, such as which
// spline segment a time falls in (the pose is continuous across segments, so
// the choice does not break the derivative).

#include <ceres/jet.h>

namespace hsmap {

inline double scalarPart(double x) { return x; }

template <class T, int N>
double scalarPart(const ceres::Jet<T, N>& x) {
  return scalarPart(x.a);
}

}  // namespace hsmap
