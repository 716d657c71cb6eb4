// fitSimilarity (solvers/similarity_fit.h): the exact similarity from exact
// data (with a lever arm and attitudes), the stated covariance against the
// spread of many noisy fits (Monte Carlo), depths and attitudes deciding the
// scale of a short sloped track as their noise says, a free direction
// reported, bad sigmas refused.
#include "solvers/similarity_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/geometry/so3.h"

namespace hsmap {
namespace {

// A short survey: 12 fixes over 4.4 m on a heading of 35 degrees, going down a
// 27 degree slope (2.2 m of depth), with a small roll and pitch wobble.
struct Track {
  std::vector<Eigen::Vector3d> p_S;  // body positions in the map frame S
  std::vector<Eigen::Quaterniond> q_S;
};

Track shortSlopedTrack() {
  Track track;
  const double heading = 35.0 * M_PI / 180.0;
  for (int i = 0; i < 12; ++i) {
    const double along = 0.4 * i;
    track.p_S.emplace_back(along * std::cos(heading), along * std::sin(heading) + 0.02 * std::sin(i),
                           0.5 * along);
    track.q_S.push_back(expSO3(Eigen::Vector3d(0.03 * std::sin(0.7 * i), 0.02 * std::cos(0.5 * i),
                                               heading)));
  }
  return track;
}

const Sim3 kTruth(0.93, expSO3(Eigen::Vector3d(0.02, -0.01, 0.4)), Eigen::Vector3d(120.0, -40.0, 38.0));
const Eigen::Vector3d kLever(0.55, 0.0, 0.35);  // camera to body, metres, on the body's axes

struct Data {
  std::vector<SimilarityFitPosition> positions;
  std::vector<SimilarityFitAttitude> attitudes;
};

// Measurements of the truth with the given noise (zero: exact).
Data measure(const Track& track, const Eigen::Vector3d& sigma_p, const Eigen::Vector3d& sigma_a,
             bool with_attitude, std::mt19937& rng, double noise_scale) {
  std::normal_distribution<double> normal;
  Data data;
  for (std::size_t i = 0; i < track.p_S.size(); ++i) {
    SimilarityFitPosition p;
    p.p_source = track.p_S[i];
    p.lever_source = track.q_S[i] * kLever;
    p.p_target = kTruth.apply(p.p_source) + kTruth.rotation() * p.lever_source;
    for (int k = 0; k < 3; ++k) p.p_target[k] += noise_scale * sigma_p[k] * normal(rng);
    p.sigma_target = sigma_p;
    data.positions.push_back(p);
    if (!with_attitude) continue;
    SimilarityFitAttitude a;
    a.q_source = track.q_S[i];
    Eigen::Vector3d noise;
    for (int k = 0; k < 3; ++k) noise[k] = noise_scale * sigma_a[k] * normal(rng);
    a.q_target = kTruth.rotation() * track.q_S[i] * expSO3(noise);
    a.sigma_rad = sigma_a;
    data.attitudes.push_back(a);
  }
  return data;
}

const Eigen::Vector3d kSigmaP(0.3, 0.3, 0.02);
const Eigen::Vector3d kSigmaA = Eigen::Vector3d(0.05, 0.05, 0.2) * M_PI / 180.0;

TEST(SimilarityFit, RecoversTheExactSimilarityWithLeverArmAndAttitude) {
  std::mt19937 rng(1);
  const Data data = measure(shortSlopedTrack(), kSigmaP, kSigmaA, true, rng, 0.0);
  const Sim3 start(1.2, Eigen::Quaterniond::Identity(), Eigen::Vector3d(100.0, 0.0, 0.0));
  const SimilarityFit fit = fitSimilarity(data.positions, data.attitudes, start);
  EXPECT_NEAR(fit.S_target_source.scale(), kTruth.scale(), 1e-9);
  EXPECT_LT(fit.S_target_source.rotation().angularDistance(kTruth.rotation()), 1e-9);
  EXPECT_LT((fit.S_target_source.translation() - kTruth.translation()).norm(), 1e-7);
  EXPECT_NEAR(fit.cost, 0.0, 1e-12);
  EXPECT_EQ(fit.residuals, 72);
  EXPECT_FALSE(fit.rank_deficient);
}

// The stated sigma of the scale is the spread of the fits' scale errors.
void expectStatedScaleSigmaMatchesSpread(bool with_attitude) {
  std::mt19937 rng(with_attitude ? 7 : 8);
  const Track track = shortSlopedTrack();
  std::vector<double> errors;
  double stated = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    const Data data = measure(track, kSigmaP, kSigmaA, with_attitude, rng, 1.0);
    const SimilarityFit fit = fitSimilarity(data.positions, data.attitudes, kTruth);
    errors.push_back(std::log(fit.S_target_source.scale() / kTruth.scale()));
    stated += fit.sigma_log_scale / 400.0;
  }
  double mean = 0.0, square = 0.0;
  for (double e : errors) mean += e / double(errors.size());
  for (double e : errors) square += (e - mean) * (e - mean) / double(errors.size() - 1);
  const double spread = std::sqrt(square);
  // 400 trials: the spread's own relative error is about 1/sqrt(800) = 3.5 %.
  EXPECT_NEAR(spread / stated, 1.0, 0.15) << "spread " << spread << " stated " << stated;
  EXPECT_LT(std::abs(mean), 4.0 * spread / std::sqrt(400.0));
}

TEST(SimilarityFit, StatedScaleSigmaIsTheSpreadOfFitsWithAttitude) {
  expectStatedScaleSigmaMatchesSpread(true);
}

TEST(SimilarityFit, StatedScaleSigmaIsTheSpreadOfFitsWithoutAttitude) {
  expectStatedScaleSigmaMatchesSpread(false);
}

// On a sloped track the 2 cm depths decide the scale; the horizontal
// positions alone (what an unweighted fit listens to) leave it ten times worse.
TEST(SimilarityFit, DepthsAndAttitudeDecideTheScaleOfAShortSlopedTrack) {
  std::mt19937 rng(3);
  const Data data = measure(shortSlopedTrack(), kSigmaP, kSigmaA, true, rng, 1.0);
  const double with_depth = fitSimilarity(data.positions, data.attitudes, kTruth).sigma_log_scale;
  Data horizontal = data;
  for (SimilarityFitPosition& p : horizontal.positions) p.sigma_target.z() = p.sigma_target.x();
  const double horizontal_only =
      fitSimilarity(horizontal.positions, horizontal.attitudes, kTruth).sigma_log_scale;
  const double without_attitude = fitSimilarity(data.positions, {}, kTruth).sigma_log_scale;
  EXPECT_LT(with_depth, 0.015);
  EXPECT_GT(horizontal_only, 5.0 * with_depth);
  EXPECT_GT(without_attitude, 1.5 * with_depth);
}

TEST(SimilarityFit, ReportsTheRollAboutAStraightTrackWithoutAttitudeAsFree) {
  std::vector<SimilarityFitPosition> positions;
  for (int i = 0; i < 6; ++i) {
    SimilarityFitPosition p;
    p.p_source = Eigen::Vector3d(0.5 * i, 0.0, 0.0);
    p.p_target = kTruth.apply(p.p_source);
    p.sigma_target = kSigmaP;
    positions.push_back(p);
  }
  const SimilarityFit fit = fitSimilarity(positions, {}, kTruth);
  EXPECT_TRUE(fit.rank_deficient);
  EXPECT_NEAR(fit.S_target_source.scale(), kTruth.scale(), 1e-9);
}

TEST(SimilarityFit, RefusesBadSigmasAndTooFewPositions) {
  std::vector<SimilarityFitPosition> positions(3);
  for (int i = 0; i < 3; ++i) positions[std::size_t(i)].p_source = Eigen::Vector3d(i, i * i, 0.0);
  positions[1].sigma_target.y() = 0.0;
  try {
    fitSimilarity(positions, {}, Sim3::identity());
    FAIL() << "a zero sigma was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "fitSimilarity: position sigmas must be finite and > 0");
  }
  positions.resize(1);
  try {
    fitSimilarity(positions, {}, Sim3::identity());
    FAIL() << "one position was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "fitSimilarity: 1 position(s); need at least 2");
  }
}

}  // namespace
}  // namespace hsmap
