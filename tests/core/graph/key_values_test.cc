#include <gtest/gtest.h>

#include <unordered_set>

#include "core/graph/key.h"
#include "core/graph/values.h"

namespace hsmap {
namespace {

TEST(Key, KindIsPartOfIdentityAndPrintsAsSymbol) {
  EXPECT_NE(X(3), L(3));
  EXPECT_EQ(X(3), X(3));
  EXPECT_EQ(X(3).toString(), "x3");
  EXPECT_EQ(L(17).toString(), "l17");
  EXPECT_EQ(S(5).toString(), "s5");
  EXPECT_EQ(E().toString(), "e0");
  EXPECT_EQ(D().toString(), "d0");
  EXPECT_EQ(K(1).toString(), "k1");
  std::unordered_set<Key> set{X(1), L(1), X(1)};
  EXPECT_EQ(set.size(), 2u);
  EXPECT_LT(X(1), X(2));
}

TEST(Values, StoresPosesInQuaternionThenTranslationLayout) {
  Values values;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  values.insertPose(X(0), q, Eigen::Vector3d(1, 2, 3));
  const double* block = values.data(X(0));
  EXPECT_DOUBLE_EQ(block[0], q.x());
  EXPECT_DOUBLE_EQ(block[3], q.w());
  EXPECT_DOUBLE_EQ(block[4], 1.0);
  EXPECT_DOUBLE_EQ(block[6], 3.0);
  EXPECT_EQ(values.size(X(0)), 7);
  EXPECT_EQ(values.tangentSize(X(0)), 6);
  EXPECT_TRUE(values.poseRotation(X(0)).isApprox(q));
}

TEST(Values, BlockAddressesStayStableAsVariablesAreAdded) {
  Values values;
  values.insertPoint(L(0), Eigen::Vector3d(1, 2, 3));
  const double* before = values.data(L(0));
  for (int i = 1; i < 1000; ++i) values.insertPoint(L(i), Eigen::Vector3d::Constant(i));
  EXPECT_EQ(values.data(L(0)), before);
  values.data(L(0))[1] = 7.0;
  EXPECT_EQ(values.point(L(0)).y(), 7.0);
}

TEST(Values, ErrorsNameTheKeyAndTheTypes) {
  Values values;
  values.insertPoint(L(2), Eigen::Vector3d::Zero());
  try {
    values.insertPoint(L(2), Eigen::Vector3d::Zero());
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "Values: key l2 is already present");
  }
  try {
    values.scalar(L(2));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "Values: l2 holds a point3, not a scalar");
  }
  try {
    values.point(L(3));
    FAIL();
  } catch (const std::out_of_range& e) {
    EXPECT_STREQ(e.what(), "Values: no variable l3");
  }
  values.insertVector(K(0), Eigen::VectorXd::Ones(4));
  EXPECT_THROW(values.updateVector(K(0), Eigen::VectorXd::Ones(5)), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap

namespace hsmap {
namespace {
TEST(Values, UpdateKeepsTheBlockAddress) {
  Values values;
  values.insertPose(X(0), Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
  const double* before = values.data(X(0));
  values.updatePose(X(0), Eigen::Quaterniond(0, 1, 0, 0), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(values.data(X(0)), before);
  EXPECT_DOUBLE_EQ(values.poseTranslation(X(0)).z(), 3.0);
  EXPECT_DOUBLE_EQ(values.poseRotation(X(0)).x(), 1.0);
}
}  // namespace
}  // namespace hsmap
