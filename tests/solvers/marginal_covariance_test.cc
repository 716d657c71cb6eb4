// Marginal covariances: a linear-Gaussian problem against the analytic
// (J^T Sigma^-1 J)^-1, a pose prior's covariance in the Se3Manifold tangent
// space, constants, and the rank-deficient (free gauge) error.

#include "solvers/marginal_covariance.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "solvers/graph_solver.h"
#include "tests/solvers/test_factors.h"

namespace hsmap {
namespace {

using test::LinearFactor;

Eigen::MatrixXd spd(std::mt19937& rng, int n, double scale) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
  return scale * (A * A.transpose() / n + 0.3 * Eigen::MatrixXd::Identity(n, n));
}

// Variables l0, l1 (points) and d0 (scalar); factors:
//   prior      l0 - a            (3, full covariance)
//   relative   l1 - l0 - b       (3, diagonal)
//   mixed      [1 0 0] l1 + 2 d0 - c   (1)
//   prior      d0 - e            (1)
//   mixed      M l0 + N l1 + g d0 - h  (2, full covariance)
// Stacking the whitened Jacobians of all factors over [l0 l1 d0] gives the
// information matrix; its inverse is the covariance.
class LinearGaussianCovarianceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 rng(3);
    std::normal_distribution<double> normal(0.0, 1.0);
    auto vec = [&](int n) {
      Eigen::VectorXd v(n);
      for (int i = 0; i < n; ++i) v[i] = normal(rng);
      return v;
    };
    auto mat = [&](int r, int c) {
      Eigen::MatrixXd m(r, c);
      for (int i = 0; i < r; ++i)
        for (int j = 0; j < c; ++j) m(i, j) = normal(rng);
      return m;
    };
    const Eigen::MatrixXd I3 = Eigen::MatrixXd::Identity(3, 3);
    Eigen::MatrixXd e0(1, 3);
    e0 << 1, 0, 0;
    add({L(0)}, {I3}, vec(3), NoiseModel::fromCovariance(spd(rng, 3, 0.04)));
    add({L(0), L(1)}, {-I3, I3}, vec(3), NoiseModel::fromSigmas(Eigen::Vector3d(0.1, 0.2, 0.3)));
    add({L(1), D(0)}, {e0, Eigen::MatrixXd::Constant(1, 1, 2.0)}, vec(1),
        NoiseModel::isotropic(1, 0.05));
    add({D(0)}, {Eigen::MatrixXd::Identity(1, 1)}, vec(1), NoiseModel::isotropic(1, 0.5));
    add({L(0), L(1), D(0)}, {mat(2, 3), mat(2, 3), mat(2, 1)}, vec(2),
        NoiseModel::fromCovariance(spd(rng, 2, 0.5)));
    values_.insertPoint(L(0), vec(3));
    values_.insertPoint(L(1), vec(3));
    values_.insertScalar(D(0), normal(rng));
  }

  void add(std::vector<Key> keys, std::vector<Eigen::MatrixXd> A, Eigen::VectorXd b,
           NoiseModel noise) {
    // Dense Jacobian over [l0 (0..2), l1 (3..5), d0 (6)].
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(b.size(), 7);
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const int column = keys[k] == L(0) ? 0 : keys[k] == L(1) ? 3 : 6;
      J.middleCols(column, A[k].cols()) = A[k];
    }
    information_ += J.transpose() * noise.covariance().inverse() * J;
    graph_.emplace<LinearFactor>(std::move(keys), std::move(A), std::move(b), std::move(noise));
  }

  FactorGraph graph_;
  Values values_;
  Eigen::MatrixXd information_ = Eigen::MatrixXd::Zero(7, 7);
};

TEST_F(LinearGaussianCovarianceTest, MarginalsEqualTheBlocksOfTheInverseInformation) {
  const Eigen::MatrixXd covariance = information_.inverse();
  GraphProblem problem(graph_, values_);
  for (const auto algorithm :
       {CovarianceOptions::Algorithm::sparse_qr, CovarianceOptions::Algorithm::dense_svd}) {
    CovarianceOptions options;
    options.algorithm = algorithm;
    const std::map<Key, Eigen::MatrixXd> marginals =
        marginalCovariances(problem, {L(0), L(1), D(0)}, options);
    ASSERT_EQ(marginals.size(), 3u);
    const Eigen::MatrixXd& l0 = marginals.at(L(0));
    const Eigen::MatrixXd& l1 = marginals.at(L(1));
    const Eigen::MatrixXd& d0 = marginals.at(D(0));
    EXPECT_LT((l0 - covariance.block(0, 0, 3, 3)).norm(), 1e-10 * covariance.norm()) << l0;
    EXPECT_LT((l1 - covariance.block(3, 3, 3, 3)).norm(), 1e-10 * covariance.norm()) << l1;
    ASSERT_EQ(d0.rows(), 1);
    EXPECT_NEAR(d0(0, 0), covariance(6, 6), 1e-10 * covariance.norm());
  }
}

TEST_F(LinearGaussianCovarianceTest, JointCovarianceKeepsTheCorrelationsInTheGivenOrder) {
  const Eigen::MatrixXd covariance = information_.inverse();
  GraphProblem problem(graph_, values_);
  const Eigen::MatrixXd joint = jointMarginalCovariance(problem, {D(0), L(0)});
  ASSERT_EQ(joint.rows(), 4);
  ASSERT_EQ(joint.cols(), 4);
  // [d0 l0] picked out of [l0 l1 d0].
  Eigen::MatrixXd expected(4, 4);
  const std::vector<int> index{6, 0, 1, 2};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) expected(i, j) = covariance(index[i], index[j]);
  EXPECT_LT((joint - expected).norm(), 1e-10 * covariance.norm()) << joint << "\n\n" << expected;
  EXPECT_GT(std::abs(joint(0, 1)), 1e-6);  // the correlation is there and not zero
}

TEST_F(LinearGaussianCovarianceTest, HoldingAVariableConstantConditionsOnIt) {
  // Conditioning on l0: the covariance of [l1 d0] is the inverse of their
  // block of the information matrix.
  GraphProblemOptions options;
  options.constant = {L(0)};
  GraphProblem problem(graph_, values_, options);
  const Eigen::MatrixXd conditioned = information_.block(3, 3, 4, 4).inverse();
  const std::map<Key, Eigen::MatrixXd> marginals = marginalCovariances(problem, {L(0), L(1), D(0)});
  EXPECT_EQ(marginals.at(L(0)), Eigen::MatrixXd::Zero(3, 3));
  EXPECT_LT((marginals.at(L(1)) - conditioned.block(0, 0, 3, 3)).norm(), 1e-10);
  EXPECT_NEAR(marginals.at(D(0))(0, 0), conditioned(3, 3), 1e-12);
}

TEST_F(LinearGaussianCovarianceTest, RejectsKeysThatAreNotVariablesOrRepeated) {
  GraphProblem problem(graph_, values_);
  try {
    marginalCovariances(problem, {L(7)});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "marginal covariance: l7 is not a variable of the problem (no factor uses it)");
  }
  try {
    jointMarginalCovariance(problem, {L(0), D(0), L(0)});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "marginal covariance: l0 is asked for twice");
  }
}

TEST(MarginalCovariance, PoseCovarianceIsInTheRightPerturbationTangentSpace) {
  // A single pose with a prior of covariance Sigma (over [rho; phi]): at the
  // optimum the residual is log(prior^-1 T exp(xi)) = xi to first order, so
  // the marginal covariance is Sigma itself.
  std::mt19937 rng(5);
  const SE3d prior = test::randomPose(rng, 10.0);
  const Eigen::MatrixXd sigma = spd(rng, 6, 0.01);
  FactorGraph graph;
  graph.emplace<test::TestPosePriorFactor>(X(0), prior, NoiseModel::fromCovariance(sigma));
  Values values;
  values.insertPose(X(0), prior.q, prior.t);
  GraphProblem problem(graph, values);
  const Eigen::MatrixXd covariance = marginalCovariances(problem, {X(0)}).at(X(0));
  ASSERT_EQ(covariance.rows(), 6);
  EXPECT_LT((covariance - sigma).norm(), 1e-10 * sigma.norm()) << covariance << "\n\n" << sigma;
}

TEST(MarginalCovariance, AFreeGaugeIsReportedAsRankDeficient) {
  // Only relative measurements between two points: the pair can slide
  // together, so J^T J is singular. With one factor J is 3x6 (fewer rows than
  // columns); with two it is 6x6 of rank 3 (numerical rank deficiency).
  auto relative = [] {
    return std::make_shared<LinearFactor>(
        std::vector<Key>{L(0), L(1)},
        std::vector<Eigen::MatrixXd>{-Eigen::MatrixXd::Identity(3, 3),
                                     Eigen::MatrixXd::Identity(3, 3)},
        Eigen::VectorXd(Eigen::Vector3d(1, 2, 3)), NoiseModel::isotropic(3, 0.1));
  };
  FactorGraph graph;
  Values values;
  values.insertPoint(L(0), Eigen::Vector3d::Zero());
  values.insertPoint(L(1), Eigen::Vector3d(1, 2, 3));
  for (int num_factors = 1; num_factors <= 2; ++num_factors) {
    graph.add(relative());
    for (const auto algorithm :
         {CovarianceOptions::Algorithm::sparse_qr, CovarianceOptions::Algorithm::dense_svd}) {
      GraphProblem problem(graph, values);
      CovarianceOptions options;
      options.algorithm = algorithm;
      SCOPED_TRACE(std::to_string(num_factors) + " factors, " +
                   (algorithm == CovarianceOptions::Algorithm::sparse_qr ? "sparse_qr" : "dense_svd"));
      try {
        marginalCovariances(problem, {L(1)}, options);
        FAIL() << "expected CovarianceRankDeficient";
      } catch (const CovarianceRankDeficient& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("marginal covariance: the problem is rank deficient"), std::string::npos) << what;
        EXPECT_NE(what.find("over the 6 free degrees of freedom"), std::string::npos) << what;
        EXPECT_NE(what.find("hold one pose constant (e.g. constant = {X(0)})"), std::string::npos) << what;
      }
    }
  }
  // Fixing the gauge (l0 constant) makes it well posed: l1 has the
  // measurement's covariance.
  GraphProblemOptions fixed;
  fixed.constant = {L(0)};
  GraphProblem problem(graph, values, fixed);
  const Eigen::MatrixXd covariance = marginalCovariances(problem, {L(1)}).at(L(1));
  // Two independent measurements of l1 - l0, each with covariance 0.01 I.
  EXPECT_LT((covariance - 0.005 * Eigen::Matrix3d::Identity()).norm(), 1e-14);
}

}  // namespace
}  // namespace hsmap
