#include "pipelines/simulate/scene/material_field.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "pipelines/simulate/scene/seabed_height_field.h"

namespace hsmap {
namespace {

constexpr int kSand = static_cast<int>(Endmember::sand);
constexpr int kSediment = static_cast<int>(Endmember::sediment);
constexpr int kRock = static_cast<int>(Endmember::rock);
constexpr int kAlgae = static_cast<int>(Endmember::algae);

std::vector<Eigen::Vector3d> randomSeabedPoints(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> north(-3.0, 23.0), east(-3.0, 3.0), depth(39.7, 40.3);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) points.emplace_back(north(rng), east(rng), depth(rng));
  return points;
}

TEST(MaterialField, AbundancesAreNonNegativeAndSumToOne) {
  const MaterialField field(1);
  for (SurfaceKind kind : {SurfaceKind::seabed, SurfaceKind::rock}) {
    for (const Eigen::Vector3d& p : randomSeabedPoints(50000, 2)) {
      const Abundances a = field.abundances(p, kind);
      float sum = 0.0f;
      for (float v : a) {
        ASSERT_GE(v, 0.0f) << p.transpose();
        sum += v;
      }
      ASSERT_NEAR(sum, 1.0f, 1e-5f) << p.transpose();
    }
  }
}

TEST(MaterialField, IsAPureFunctionOfSeedPositionAndKind) {
  const MaterialField a(5), b(5), other(6);
  const auto points = randomSeabedPoints(2000, 3);
  int differs_by_seed = 0, differs_by_kind = 0;
  for (const Eigen::Vector3d& p : points) {
    const Abundances first = a.abundances(p, SurfaceKind::seabed);
    EXPECT_EQ(first, b.abundances(p, SurfaceKind::seabed));
    EXPECT_EQ(first, a.abundances(p, SurfaceKind::seabed));
    differs_by_seed += first != other.abundances(p, SurfaceKind::seabed);
    differs_by_kind += first != a.abundances(p, SurfaceKind::rock);
  }
  // Pure sand under both seeds is the same vector, so not every point differs.
  EXPECT_GT(differs_by_seed, 1500);
  EXPECT_GT(differs_by_kind, 1900);
}

TEST(MaterialField, EveryEndmemberOccursAndRockSurfacesAreRockDominated) {
  const MaterialField field(1);
  std::array<double, kEndmemberCount> seabed_max{}, seabed_mean{}, rock_mean{};
  const auto points = randomSeabedPoints(40000, 4);
  for (const Eigen::Vector3d& p : points) {
    const Abundances s = field.abundances(p, SurfaceKind::seabed);
    const Abundances r = field.abundances(p, SurfaceKind::rock);
    for (int k = 0; k < kEndmemberCount; ++k) {
      seabed_max[k] = std::max<double>(seabed_max[k], s[k]);
      seabed_mean[k] += s[k] / points.size();
      rock_mean[k] += r[k] / points.size();
    }
  }
  // Each endmember is nearly pure somewhere on the seabed (the unmixing needs
  // pure pixels), and none is negligible overall.
  for (int k = 0; k < kEndmemberCount; ++k) {
    EXPECT_GT(seabed_max[k], 0.8) << endmemberName(static_cast<Endmember>(k));
    EXPECT_GT(seabed_mean[k], 0.02) << endmemberName(static_cast<Endmember>(k));
  }
  EXPECT_GT(seabed_mean[kSand] + seabed_mean[kSediment], 0.6);
  EXPECT_GT(rock_mean[kRock], 0.6);
  EXPECT_GT(rock_mean[kAlgae], 0.02);
  EXPECT_GT(rock_mean[kSediment], 0.05);
}

// Pearson correlation of f(p) and f(p + lag * d) over random seabed points p
// and random horizontal directions d.
double correlationAtLag(const std::function<double(const Eigen::Vector3d&)>& f, double lag_m,
                        int samples) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * 3.14159265358979323846);
  const auto points = randomSeabedPoints(samples, 12);
  std::vector<double> x, y;
  for (const Eigen::Vector3d& p : points) {
    const double a = angle(rng);
    x.push_back(f(p));
    y.push_back(f(p + lag_m * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0)));
  }
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / x.size();
  const double my = std::accumulate(y.begin(), y.end(), 0.0) / y.size();
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  return sxy / std::sqrt(sxx * syy);
}

TEST(MaterialField, VariesAtMetreDecimetreAndCentimetreScales) {
  const MaterialField field(1);
  const auto fraction = [&](int k) {
    return [&field, k](const Eigen::Vector3d& p) {
      return static_cast<double>(field.abundances(p, SurfaceKind::seabed)[k]);
    };
  };
  // Sand/sediment areas, seen through a 0.4 m box average that removes the
  // pebbles and patches painted over them: the same a decimetre away,
  // unrelated 8 m away.
  const auto areaSediment = [&](const Eigen::Vector3d& p) {
    double sum = 0.0;
    for (int i = -2; i <= 2; ++i) {
      for (int j = -2; j <= 2; ++j) {
        sum += field.abundances(p + Eigen::Vector3d(0.1 * i, 0.1 * j, 0.0),
                                SurfaceKind::seabed)[kSediment];
      }
    }
    return sum / 25.0;
  };
  EXPECT_GT(correlationAtLag(areaSediment, 0.1, 4000), 0.9);
  EXPECT_LT(correlationAtLag(areaSediment, 8.0, 4000), 0.3);
  // Algae patches: coherent over a centimetre, unrelated half a metre away.
  EXPECT_GT(correlationAtLag(fraction(kAlgae), 0.01, 20000), 0.8);
  EXPECT_LT(correlationAtLag(fraction(kAlgae), 0.5, 20000), 0.2);
  // Pebbles: coherent over a millimetre, unrelated 5 cm away.
  EXPECT_GT(correlationAtLag(fraction(kRock), 0.001, 20000), 0.7);
  EXPECT_LT(correlationAtLag(fraction(kRock), 0.05, 20000), 0.2);
}

// Top-down orthographic grey image of a width_m x (width_m * 9/16) patch of
// the bare seabed centred on (north, east), 960x540 pixels, north up. Each
// pixel averages 2x2 samples (a camera integrates over its pixel; point
// samples would alias the finest grit into pixel noise and inflate the
// corner count). Luminance from the reflectance at three wavelengths.
cv::Mat renderTopDown(const MaterialField& field, const SeabedHeightField& seabed, double north,
                      double east, double width_m, SurfaceKind kind) {
  constexpr int kWidth = 960, kHeight = 540;
  const Eigen::MatrixXf E = MaterialField::endmemberMatrix({610.0, 540.0, 460.0});
  const Eigen::RowVectorXf luminance = Eigen::RowVector3f(0.3f, 0.6f, 0.1f) * E;
  const double pixel_m = width_m / kWidth;
  cv::Mat image(kHeight, kWidth, CV_32F);
  tbb::parallel_for(0, kHeight, [&](int row) {
    for (int col = 0; col < kWidth; ++col) {
      float sum = 0.0f;
      // The seabed height at the pixel centre serves its 4 samples: it
      // changes by well under a millimetre across a pixel.
      const double z = seabed.z(north - (row + 0.5 - kHeight / 2.0) * pixel_m,
                                east + (col + 0.5 - kWidth / 2.0) * pixel_m);
      for (int sub = 0; sub < 4; ++sub) {
        const double e = east + (col + 0.25 + 0.5 * (sub % 2) - kWidth / 2.0) * pixel_m;
        const double n = north - (row + 0.25 + 0.5 * (sub / 2) - kHeight / 2.0) * pixel_m;
        const Abundances a = field.abundances(Eigen::Vector3d(n, e, z), kind);
        for (int k = 0; k < kEndmemberCount; ++k) sum += luminance[k] * a[k];
      }
      image.at<float>(row, col) = sum / 4.0f;
    }
  });
  return image;
}

// Shi-Tomasi corners as the front end will detect them, and how many fall in
// each cell of a 4 x 3 grid over the image.
struct CornerCount {
  int total = 0;
  int fewest_in_a_cell = 0;
};
CornerCount countCorners(const cv::Mat& image) {
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(image, corners, 3000, 0.01, 10);
  std::array<int, 12> cells{};
  for (const auto& c : corners) {
    const int cx = std::min(3, static_cast<int>(c.x / (image.cols / 4.0)));
    const int cy = std::min(2, static_cast<int>(c.y / (image.rows / 3.0)));
    ++cells[cy * 4 + cx];
  }
  return {static_cast<int>(corners.size()), *std::min_element(cells.begin(), cells.end())};
}

TEST(MaterialField, FlatSeabedCarriesTrackableTextureAtEveryAltitude) {
  SeabedSceneConfig config;
  config.terrain = TerrainPreset::flat;
  const SeabedHeightField seabed(config);
  const MaterialField field(config.seed);
  // The places to look at: the most sand-rich and the most sediment-rich of
  // candidate image centres along the track, plus a fixed one.
  std::vector<double> norths;
  for (double n = 0.0; n <= 20.0; n += 1.0) norths.push_back(n);
  const auto sedimentAround = [&](double n) {
    double sum = 0.0;
    for (double dn = -0.6; dn <= 0.6; dn += 0.1) {
      for (double de = -1.2; de <= 1.2; de += 0.1) {
        sum += field.abundances(Eigen::Vector3d(n + dn, de, seabed.z(n + dn, de)),
                                SurfaceKind::seabed)[kSediment];
      }
    }
    return sum;
  };
  const auto [sandiest, muddiest] = std::minmax_element(
      norths.begin(), norths.end(),
      [&](double a, double b) { return sedimentAround(a) < sedimentAround(b); });
  struct View {
    double north, east, width_m;
  };
  // 2.4 m wide at 2 m altitude, 1.2 m at 1 m, 3.6 m at 3 m.
  const std::vector<View> views = {{*sandiest, 0.0, 2.4},
                                   {*muddiest, 0.0, 2.4},
                                   {*muddiest, 0.3, 1.2},
                                   {*sandiest, -0.3, 1.2},
                                   {10.0, 0.5, 3.6}};
  for (const View& v : views) {
    const CornerCount count =
        countCorners(renderTopDown(field, seabed, v.north, v.east, v.width_m, SurfaceKind::seabed));
    EXPECT_GE(count.total, 300) << "north " << v.north << " width " << v.width_m;
    EXPECT_GE(count.fewest_in_a_cell, 10) << "north " << v.north << " width " << v.width_m;
  }
}

TEST(MaterialField, RockSurfacesCarryTrackableTextureToo) {
  SeabedSceneConfig config;
  config.terrain = TerrainPreset::flat;
  const SeabedHeightField seabed(config);
  const MaterialField field(3);
  const CornerCount count =
      countCorners(renderTopDown(field, seabed, 4.0, 0.0, 2.4, SurfaceKind::rock));
  EXPECT_GE(count.total, 300);
  EXPECT_GE(count.fewest_in_a_cell, 10);
}

TEST(MaterialField, EndmemberMatrixHoldsTheLibrarySpectra) {
  const std::vector<double> wavelengths = {400.0, 551.5, 675.0, 800.0};
  const Eigen::MatrixXf E = MaterialField::endmemberMatrix(wavelengths);
  ASSERT_EQ(E.rows(), 4);
  ASSERT_EQ(E.cols(), kEndmemberCount);
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < kEndmemberCount; ++k) {
      EXPECT_EQ(E(i, k), static_cast<float>(
                             endmemberReflectance(static_cast<Endmember>(k), wavelengths[i])));
    }
  }
  // A mixture reflects the abundance-weighted spectra.
  const MaterialField field(1);
  const Abundances a = field.abundances(Eigen::Vector3d(1.0, 0.2, 40.0), SurfaceKind::seabed);
  const Eigen::VectorXf r = E * Eigen::Map<const Eigen::VectorXf>(a.data(), kEndmemberCount);
  for (int i = 0; i < 4; ++i) {
    EXPECT_GE(r[i], E.row(i).minCoeff() - 1e-6f);
    EXPECT_LE(r[i], E.row(i).maxCoeff() + 1e-6f);
  }
  EXPECT_THROW(MaterialField::endmemberMatrix({300.0}), std::invalid_argument);
  EXPECT_EQ(MaterialField::endmemberMatrix({}).rows(), 0);
}

}  // namespace
}  // namespace hsmap
