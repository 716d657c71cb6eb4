// Marine snow (optics.marine_snow, rgb_marine_snow.h): over a flat seabed
// without sensor noise, the frame with snow less the frame without it shows
// bright dots, about as many as the density times the water's volume in view
// (up to the seabed) predicts; the next frame's particles are others; and a
// survey with snow has the same truth/scene.ply as one without.
#include <fstream>
#include <iterator>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "core/util/input_error.h"
#include "pipelines/simulate/simulate_survey.h"
#include "pipelines/simulate/simulation_config_yaml.h"
#include "tests/pipelines/simulate/flat_water.h"
#include "tests/pipelines/simulate/tiny_survey.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::FlatWater;
testing::TinySurveyCleanup cleanup;

MarineSnowConfig snow() {
  MarineSnowConfig config;
  config.enabled = true;
  config.density_per_m3 = 150.0;
  config.diameter_min_mm = 1.0;
  config.diameter_max_mm = 3.0;
  return config;
}

// Pixels brighter than the snow-free frame by more than 4 DN in green.
cv::Mat snowMask(const cv::Mat& with, const cv::Mat& without) {
  cv::Mat difference;
  cv::subtract(with, without, difference, cv::noArray(), CV_16SC3);
  std::vector<cv::Mat> channels;
  cv::split(difference, channels);
  return channels[1] > 4;
}

int dots(const cv::Mat& mask) {
  cv::Mat labels;
  return cv::connectedComponents(mask, labels, 8) - 1;
}

TEST(RgbMarineSnow, BrightDotsAtTheStatedDensityDifferentInEveryFrame) {
  const FlatWater clear(1.0, false);
  const FlatWater snowy(1.0, false, snow());
  const cv::Mat without = clear.rgbFrame(0);
  const cv::Mat mask0 = snowMask(snowy.rgbFrame(0), without);
  const cv::Mat mask1 = snowMask(snowy.rgbFrame(1), without);
  // The water in view up to the seabed, from the nearest particle depth.
  const PinholeRadtanParameters& camera = snowy.config.rgb.camera;
  MarineSnowConfig to_seabed = snow();
  to_seabed.max_range_m = testing::kAltitude;
  const double expected = snow().density_per_m3 * marineSnowVolume(to_seabed, camera);
  const int count0 = dots(mask0);
  const int count1 = dots(mask1);
  std::cout << "dots: " << count0 << " and " << count1 << " in two frames, " << expected
            << " particles expected in front of the seabed\n";
  // Dots can merge or be too faint (far, small, outside the beams): the same
  // order, not the same number.
  for (int count : {count0, count1}) {
    EXPECT_GT(count, 0.4 * expected);
    EXPECT_LT(count, 1.2 * expected);
  }
  // Another frame, other particles: few of the bright pixels coincide.
  const int overlap = cv::countNonZero(mask0 & mask1);
  EXPECT_LT(overlap, 0.2 * std::min(cv::countNonZero(mask0), cv::countNonZero(mask1)));
  // Without snow configured, the frame is the snow-free frame.
  EXPECT_EQ(cv::countNonZero(snowMask(clear.rgbFrame(0), without)), 0);
}

std::vector<char> bytesOf(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
}

TEST(RgbMarineSnow, IsNotInTheScene) {
  const auto& tiny = testing::tinySurvey();
  SimulationConfig config = tiny.config;
  config.optics.marine_snow = snow();
  testing::TempFolder folder("marine_snow_scene");
  std::ostringstream log;
  simulateSurvey(config, folder / "survey", log);
  const std::vector<char> scene = bytesOf(folder / "survey" / "truth" / "scene.ply");
  ASSERT_FALSE(scene.empty());
  EXPECT_TRUE(scene == bytesOf(tiny.folder / "truth" / "scene.ply"));
  // ... but in the frames: the first frame differs from tiny's.
  EXPECT_FALSE(bytesOf(folder / "survey" / "rgb" / "frame_000000.png") ==
               bytesOf(tiny.folder / "rgb" / "frame_000000.png"));
}

TEST(RgbMarineSnow, SettingsAreReadStrictly) {
  testing::TempFolder folder("marine_snow_yaml");
  const auto path = folder / "sim.yaml";
  auto read = [&](const std::string& body) {
    std::ofstream(path) << "format: hsmap-simulation/1\npreset: tiny\n" << body;
    return readSimulationConfig(path);
  };
  EXPECT_FALSE(read("").optics.marine_snow.enabled);
  EXPECT_TRUE(read("optics: {marine_snow: {}}\n").optics.marine_snow.enabled);
  const MarineSnowConfig set =
      read("optics: {marine_snow: {density_per_m3: 40, diameter_min_mm: 1, diameter_max_mm: 2, albedo: 0.3}}\n")
          .optics.marine_snow;
  EXPECT_EQ(set.density_per_m3, 40.0);
  EXPECT_EQ(set.diameter_min_mm, 1.0);
  EXPECT_EQ(set.diameter_max_mm, 2.0);
  EXPECT_EQ(set.albedo, 0.3);
  for (const char* wrong : {"optics: {marine_snow: {diameter_min_mm: 3, diameter_max_mm: 2}}\n",
                            "optics: {marine_snow: {albedo: 2}}\n", "optics: {marine_snow: {size: 2}}\n"}) {
    try {
      read(wrong);
      ADD_FAILURE() << "no error for " << wrong;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("line 3, key optics.marine_snow"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace hsmap
