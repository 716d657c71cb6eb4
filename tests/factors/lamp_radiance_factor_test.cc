#include "factors/lamp_radiance_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::scalarBlock;
using test::tangentJacobiansMatchNumeric;
using test::vectorBlock;

LampRadianceResidual twoLamps() {
  LampRadianceResidual m;
  m.dn = 800.0;
  m.response_dn = 5000.0;
  m.uhi_range_m = 1.6;
  m.lamps = {{1.7, 0.9, 0.2}, {1.9, 0.7, 0.45}};
  return m;
}

TEST(LampRadianceFactor, NamesItsMeasurementAndKeys) {
  const LampRadianceFactor factor(C(3), O(3), R(17), M(0), twoLamps(), NoiseModel::isotropic(1, 5.0),
                                  RobustLoss::cauchy(3.0));
  EXPECT_EQ(factor.name(), "LampRadianceFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{C(3), O(3), R(17), M(0)}));
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(), (std::vector<int32_t>{1, 1, 1, 2}));
}

TEST(LampRadianceFactor, PredictsTheContractsModel) {
  const LampRadianceResidual m = twoLamps();
  const LampRadianceFactor factor(C(0), O(0), R(0), M(0), m, NoiseModel::isotropic(1, 5.0), RobustLoss::none());
  const double c = 0.15, o = 12.0, rho = 0.3, m1 = -2.0, m2 = 0.4;
  double expected = 0.0;
  for (const LampPath& lamp : m.lamps) {
    const double t = lamp.off_axis_rad;
    expected += std::exp(m1 * t * t + m2 * t * t * t * t) * lamp.cos_incidence / (lamp.range_m * lamp.range_m) *
                std::exp(-c * (lamp.range_m + m.uhi_range_m));
  }
  expected = m.response_dn * rho * expected + o;
  const auto evaluation = evaluate(*factor.createCostFunction(),
                                   {scalarBlock(c), scalarBlock(o), scalarBlock(std::log(rho)),
                                    vectorBlock(Eigen::Vector2d(m1, m2))});
  ASSERT_TRUE(evaluation.ok);
  EXPECT_NEAR(evaluation.residual[0], expected - m.dn, 1e-9);
  // B(0) = 1 whatever the coefficients: a lamp on its axis is K's measurement.
  const double beam[2] = {-3.0, 1.5};
  EXPECT_DOUBLE_EQ(lampBeam(0.0, beam), 1.0);
}

TEST(LampRadianceFactor, JacobiansMatchNumeric) {
  const LampRadianceFactor factor(C(0), O(0), R(0), M(0), twoLamps(), NoiseModel::isotropic(1, 5.0),
                                  RobustLoss::none());
  EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(),
                                           {scalarBlock(0.2), scalarBlock(3.0), scalarBlock(std::log(0.25)),
                                            vectorBlock(Eigen::Vector2d(-1.5, 0.2))}));
}

TEST(LampRadianceFactor, RejectsBadArguments) {
  LampRadianceResidual no_lamp = twoLamps();
  no_lamp.lamps.clear();
  EXPECT_THROW(LampRadianceFactor(C(0), O(0), R(0), M(0), no_lamp, NoiseModel::isotropic(1, 1.0), RobustLoss::none()),
               std::invalid_argument);
  LampRadianceResidual grazing = twoLamps();
  grazing.lamps[1].cos_incidence = 0.0;
  EXPECT_THROW(LampRadianceFactor(C(0), O(0), R(0), M(0), grazing, NoiseModel::isotropic(1, 1.0), RobustLoss::none()),
               std::invalid_argument);
  LampRadianceResidual dark = twoLamps();
  dark.response_dn = 0.0;
  EXPECT_THROW(LampRadianceFactor(C(0), O(0), R(0), M(0), dark, NoiseModel::isotropic(1, 1.0), RobustLoss::none()),
               std::invalid_argument);
  EXPECT_THROW(LampRadianceFactor(C(0), O(0), R(0), M(0), twoLamps(), NoiseModel::isotropic(2, 1.0),
                                  RobustLoss::none()),
               std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
