#include "pipelines/simulate/scene/spectral_library.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace hsmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Endmember> allEndmembers() {
  std::vector<Endmember> all;
  for (int k = 0; k < kEndmemberCount; ++k) all.push_back(static_cast<Endmember>(k));
  return all;
}

double R(Endmember e, double wavelength_nm) { return endmemberReflectance(e, wavelength_nm); }

// Spectral angle (degrees) between two endmembers sampled every nm in [lo, hi].
double spectralAngleDeg(Endmember a, Endmember b, int lo, int hi) {
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (int w = lo; w <= hi; ++w) {
    ab += R(a, w) * R(b, w);
    aa += R(a, w) * R(a, w);
    bb += R(b, w) * R(b, w);
  }
  return std::acos(ab / std::sqrt(aa * bb)) * 180.0 / kPi;
}

TEST(SpectralLibrary, NamesEveryEndmember) {
  EXPECT_STREQ(endmemberName(Endmember::sand), "sand");
  EXPECT_STREQ(endmemberName(Endmember::sediment), "sediment");
  EXPECT_STREQ(endmemberName(Endmember::rock), "rock");
  EXPECT_STREQ(endmemberName(Endmember::coral), "coral");
  EXPECT_STREQ(endmemberName(Endmember::algae), "algae");
}

TEST(SpectralLibrary, ReflectancesLieStrictlyBetweenZeroAndOne) {
  for (Endmember e : allEndmembers()) {
    for (double w = 350.0; w <= 1000.0; w += 0.5) {
      const double r = R(e, w);
      EXPECT_GT(r, 0.0) << endmemberName(e) << " at " << w;
      EXPECT_LT(r, 1.0) << endmemberName(e) << " at " << w;
    }
  }
}

TEST(SpectralLibrary, SpectraAreSmooth) {
  for (Endmember e : allEndmembers()) {
    double max_step = 0.0, max_curvature = 0.0;
    for (int w = 351; w < 1000; ++w) {
      max_step = std::max(max_step, std::abs(R(e, w + 1) - R(e, w)));
      max_curvature = std::max(max_curvature, std::abs(R(e, w + 1) - 2 * R(e, w) + R(e, w - 1)));
    }
    EXPECT_LT(max_step, 0.01) << endmemberName(e);        // per nm
    EXPECT_LT(max_curvature, 0.001) << endmemberName(e);  // per nm^2
  }
}

TEST(SpectralLibrary, EveryPairDiffersBySpectralAngle) {
  for (Endmember a : allEndmembers()) {
    for (Endmember b : allEndmembers()) {
      if (static_cast<int>(a) >= static_cast<int>(b)) continue;
      EXPECT_GT(spectralAngleDeg(a, b, 400, 800), 8.0)
          << endmemberName(a) << " vs " << endmemberName(b);
    }
  }
}

TEST(SpectralLibrary, ShapesFollowTheMaterials) {
  // Sand: the brightest everywhere in the visible, rising slowly.
  for (int w = 400; w <= 700; w += 10) {
    for (Endmember e : allEndmembers()) {
      if (e != Endmember::sand) {
        EXPECT_GT(R(Endmember::sand, w), R(e, w)) << w;
      }
    }
  }
  EXPECT_GT(R(Endmember::sand, 700), R(Endmember::sand, 450));
  // Sediment: darker than sand, redder than blue (brownish).
  EXPECT_GT(R(Endmember::sediment, 650), 1.5 * R(Endmember::sediment, 450));
  // Rock: grey, within 10% of its mean over 400-800 nm.
  for (int w = 400; w <= 800; w += 10) EXPECT_NEAR(R(Endmember::rock, w), 0.15, 0.015) << w;
  // Coral: low blue, orange-red maximum, absorption dip at 675 nm.
  EXPECT_LT(R(Endmember::coral, 450), 0.05);
  EXPECT_GT(R(Endmember::coral, 630), 4.0 * R(Endmember::coral, 450));
  EXPECT_LT(R(Endmember::coral, 675), R(Endmember::coral, 650) - 0.05);
  EXPECT_LT(R(Endmember::coral, 675), R(Endmember::coral, 700) - 0.03);
  // Algae: chlorophyll absorption at 440 and 675 nm around a green bump, red edge.
  EXPECT_GT(R(Endmember::algae, 555), 2.0 * R(Endmember::algae, 440));
  EXPECT_GT(R(Endmember::algae, 555), 2.0 * R(Endmember::algae, 675));
  EXPECT_GT(R(Endmember::algae, 760), 4.0 * R(Endmember::algae, 555));
}

TEST(SpectralLibrary, RejectsWavelengthsOutsideItsDomain) {
  EXPECT_NO_THROW(R(Endmember::rock, 350.0));
  EXPECT_NO_THROW(R(Endmember::rock, 1000.0));
  try {
    R(Endmember::sand, 349.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "endmemberReflectance: wavelength must be in [350, 1000] nm, got 349");
  }
  EXPECT_THROW(R(Endmember::algae, 1000.5), std::invalid_argument);
  EXPECT_THROW(R(Endmember::algae, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
