#include "pipelines/simulate/motion/natural_cubic_spline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace hsmap {
namespace {

TEST(NaturalCubicSplineTest, MatchesTheHandSolvedThreeKnotSpline) {
  // Knots (0,0), (1,1), (2,0): 4 M_1 = 6 (-1 - 1), M_1 = -3; at x = 0.5,
  // y = 0.5 + (0.125 - 0.5) (-3) / 6 = 0.6875.
  const NaturalCubicSpline spline({0.0, 1.0, 2.0}, {0.0, 1.0, 0.0});
  EXPECT_DOUBLE_EQ(spline.value(0.5), 0.6875);
  EXPECT_DOUBLE_EQ(spline.value(1.5), 0.6875);
  EXPECT_DOUBLE_EQ(spline.secondDerivative(1.0), -3.0);
  EXPECT_DOUBLE_EQ(spline.secondDerivative(0.5), -1.5);
  // y' at 0: (1 - 0) / 1 + ((1 - 3) * 0 + (0 - 1) * (-3)) / 6 = 1.5.
  EXPECT_DOUBLE_EQ(spline.derivative(0.0), 1.5);
}

TEST(NaturalCubicSplineTest, InterpolatesKnotsAndIsC2AtThem) {
  std::vector<double> x, y;
  for (int i = 0; i < 30; ++i) {
    x.push_back(0.3 * i + 0.05 * std::sin(i));  // uneven spacing
    y.push_back(std::sin(0.7 * x.back()) + 0.1 * (i % 3));
  }
  const NaturalCubicSpline spline(x, y);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(spline.value(x[i]), y[i], 1e-12);
  const double h = 1e-7;
  for (std::size_t i = 1; i + 1 < x.size(); ++i) {
    EXPECT_NEAR(spline.value(x[i] - h), spline.value(x[i] + h), 1e-5) << "knot " << i;
    EXPECT_NEAR(spline.derivative(x[i] - h), spline.derivative(x[i] + h), 1e-5) << "knot " << i;
    EXPECT_NEAR(spline.secondDerivative(x[i] - h), spline.secondDerivative(x[i] + h), 1e-4)
        << "knot " << i;
  }
  // Natural end conditions.
  EXPECT_EQ(spline.secondDerivative(x.front()), 0.0);
  EXPECT_NEAR(spline.secondDerivative(x.back()), 0.0, 1e-12);
}

TEST(NaturalCubicSplineTest, DerivativesMatchFiniteDifferences) {
  const NaturalCubicSpline spline({0.0, 0.5, 1.5, 2.0, 3.5}, {1.0, -1.0, 2.0, 0.5, 0.0});
  const double h = 1e-6;
  for (double x = 0.1; x < 3.4; x += 0.237) {
    EXPECT_NEAR(spline.derivative(x), (spline.value(x + h) - spline.value(x - h)) / (2 * h), 1e-6);
    EXPECT_NEAR(spline.secondDerivative(x),
                (spline.derivative(x + h) - spline.derivative(x - h)) / (2 * h), 1e-5);
  }
}

TEST(NaturalCubicSplineTest, ReproducesAStraightLineAndExtendsLinearly) {
  const NaturalCubicSpline spline({0.0, 1.0, 3.0, 4.0}, {1.0, 3.0, 7.0, 9.0});  // y = 2x + 1
  for (double x = -2.0; x <= 6.0; x += 0.25) {
    EXPECT_NEAR(spline.value(x), 2.0 * x + 1.0, 1e-12);
    EXPECT_NEAR(spline.derivative(x), 2.0, 1e-12);
  }
  // A curved spline continues along its end tangent.
  const NaturalCubicSpline curved({0.0, 1.0, 2.0}, {0.0, 1.0, 0.0});
  EXPECT_DOUBLE_EQ(curved.value(3.0), curved.value(2.0) + curved.derivative(2.0));
  EXPECT_EQ(curved.secondDerivative(-1.0), 0.0);
}

TEST(NaturalCubicSplineTest, RejectsBadKnots) {
  try {
    NaturalCubicSpline({0.0}, {0.0});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "NaturalCubicSpline: expected as many values as knots, at least 2, got 1 knots "
                 "and 1 values");
  }
  try {
    NaturalCubicSpline({0.0, 1.0, 1.0}, {0.0, 1.0, 2.0});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "NaturalCubicSpline: knots must be strictly increasing");
  }
  EXPECT_THROW(NaturalCubicSpline({0.0, 1.0}, {0.0, NAN}), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
