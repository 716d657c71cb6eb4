#include "core/survey/water_estimate.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/survey/run_calibration.h"
#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

WaterEstimate example() {
  WaterEstimate water;
  water.attenuation_per_m = {0.12, 0.3456789012345, 2.5};
  water.attenuation_sigma_per_m = {0.01, std::nullopt, 0.2};
  water.backscatter_dn = {0.0, 0.0, 0.0};
  water.backscatter_sigma_dn = {std::nullopt, std::nullopt, std::nullopt};
  water.beam = {-1.02, -0.15};
  water.beam_sigma = {0.05, std::nullopt};
  water.warnings = {"radiometry: the survey does not determine c(λ) at 1 of 3 bands"};
  return water;
}

void expectSame(const WaterEstimate& a, const WaterEstimate& b) {
  EXPECT_EQ(a.attenuation_per_m, b.attenuation_per_m);
  EXPECT_EQ(a.attenuation_sigma_per_m, b.attenuation_sigma_per_m);
  EXPECT_EQ(a.backscatter_dn, b.backscatter_dn);
  EXPECT_EQ(a.backscatter_sigma_dn, b.backscatter_sigma_dn);
  EXPECT_EQ(a.beam, b.beam);
  EXPECT_EQ(a.beam_sigma, b.beam_sigma);
}

TEST(WaterEstimate, WaterYamlReadsBackExactly) {
  const testing::TempFolder folder("water-estimate");
  const WaterEstimate water = example();
  writeWaterEstimate(folder / "water.yaml", water);
  const WaterEstimate back = readWaterEstimate(folder / "water.yaml");
  expectSame(back, water);
  EXPECT_EQ(back.warnings, water.warnings);
}

TEST(WaterEstimate, CalibrationYamlCarriesTheWaterBlock) {
  const testing::TempFolder folder("water-calibration");
  RunCalibration calibration;
  calibration.variant = "sequential";
  calibration.water = example();
  calibration.water->warnings.clear();
  writeRunCalibration(folder / "calibration.yaml", calibration);
  const RunCalibration back = readRunCalibration(folder / "calibration.yaml");
  ASSERT_TRUE(back.water.has_value());
  expectSame(*back.water, *calibration.water);
  calibration.water.reset();
  writeRunCalibration(folder / "plain.yaml", calibration);
  EXPECT_FALSE(readRunCalibration(folder / "plain.yaml").water.has_value());
}

TEST(WaterEstimate, ABadBlockNamesTheFileLineAndKey) {
  const testing::TempFolder folder("water-bad");
  std::ofstream(folder / "water.yaml") << "format: hsmap-water/1\n"
                                          "water:\n"
                                          "  attenuation_per_m: [0.1, 0.2]\n"
                                          "  attenuation_sigma_per_m: [0.01, null]\n"
                                          "  backscatter_dn: [0, 0, 0]\n"
                                          "  backscatter_sigma_dn: [null, null]\n"
                                          "  beam: {model: exp-even-polynomial, coefficients: [-1, 0], coefficients_sigma: [null, null]}\n"
                                          "warnings: []\n";
  try {
    readWaterEstimate(folder / "water.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where(), "line 5, key water.backscatter_dn");
    EXPECT_NE(error.detail().find("expected a list of 2 numbers"), std::string::npos) << error.detail();
  }
  std::ofstream(folder / "typo.yaml") << "format: hsmap-water/1\n"
                                         "water:\n"
                                         "  attenuation_per_m: [0.1]\n"
                                         "  attenuation_sigma_per_m: [0.01]\n"
                                         "  backscatter_dn: [0]\n"
                                         "  backscatter_sigma_dn: [null]\n"
                                         "  beam: {model: exp-even-polynomial, coefficients: [-1, 0], coefficients_sigma: [null, null]}\n"
                                         "  attenuaton: 3\n"
                                         "warnings: []\n";
  try {
    readWaterEstimate(folder / "typo.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where(), "line 8, key water.attenuaton");
    EXPECT_EQ(error.detail(), "unknown key");
  }
}

}  // namespace
}  // namespace hsmap
