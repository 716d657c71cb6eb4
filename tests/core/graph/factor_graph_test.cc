#include "core/graph/factor_graph.h"

#include <gtest/gtest.h>

namespace hsmap {
namespace {

class TestFactor : public Factor {
 public:
  TestFactor(std::vector<Key> keys, int dimension)
      : Factor(std::move(keys), NoiseModel::isotropic(dimension, 1.0), RobustLoss::none()) {}
  std::string name() const override { return "TestFactor"; }
};

TEST(FactorGraph, IndexesFactorsByTheVariablesTheyTouch) {
  FactorGraph graph;
  graph.emplace<TestFactor>(std::vector<Key>{X(0), L(0)}, 2);
  graph.emplace<TestFactor>(std::vector<Key>{X(1), L(0)}, 2);
  graph.emplace<TestFactor>(std::vector<Key>{X(1)}, 3);
  EXPECT_EQ(graph.size(), 3u);
  EXPECT_EQ(graph.residualDimension(), 7u);
  EXPECT_EQ(graph.factorsOf(L(0)), (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(graph.factorsOf(X(1)), (std::vector<std::size_t>{1, 2}));
  EXPECT_TRUE(graph.factorsOf(X(9)).empty());
  EXPECT_EQ(graph.keys(), (std::vector<Key>{X(0), X(1), L(0)}));
  EXPECT_EQ(graph.countByName().at("TestFactor"), 3u);
}

TEST(FactorGraph, ReportsVariablesMissingFromValues) {
  FactorGraph graph;
  graph.emplace<TestFactor>(std::vector<Key>{X(0), L(4)}, 2);
  Values values;
  values.insertPose(X(0), Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
  EXPECT_EQ(graph.missingKeys(values), std::vector<Key>{L(4)});
}

TEST(FactorGraph, RejectsAFactorThatNamesAVariableTwice) {
  EXPECT_THROW(TestFactor({X(0), X(0)}, 2), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
