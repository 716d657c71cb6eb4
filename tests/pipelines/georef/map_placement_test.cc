// georef/map_placement.yaml (pipelines/georef/map_placement.h): written and
// read back exactly, a bad value named by its line and key, and the warning
// only for a scale known worse than 1 %.
#include "pipelines/georef/map_placement.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

MapPlacement example() {
  MapPlacement p;
  p.fixes = 12;
  p.attitude_measured = false;
  p.scale_sigma = 0.0131;
  p.scale_sigma_without_attitude = 0.0131;
  p.scale_sigma_without_depth = 0.071;
  p.rotation_sigma_deg = Eigen::Vector3d(49.5, 2.4, 2.3);
  p.position_sigma_m = Eigen::Vector3d(0.067, 0.31, 0.019);
  p.correction_scale = 0.99998;
  p.correction_rotation_deg = 0.97;
  p.correction_translation_m = 0.0015;
  return p;
}

TEST(MapPlacementFile, RoundTripsExactly) {
  const testing::TempFolder temp("map-placement");
  const MapPlacement written = example();
  writeMapPlacement(temp / "map_placement.yaml", written);
  const MapPlacement read = readMapPlacement(temp / "map_placement.yaml");
  EXPECT_EQ(read.fixes, written.fixes);
  EXPECT_EQ(read.attitude_measured, written.attitude_measured);
  EXPECT_EQ(read.scale_sigma, written.scale_sigma);
  EXPECT_EQ(read.scale_sigma_without_attitude, written.scale_sigma_without_attitude);
  EXPECT_EQ(read.scale_sigma_without_depth, written.scale_sigma_without_depth);
  EXPECT_EQ(read.rotation_sigma_deg, written.rotation_sigma_deg);
  EXPECT_EQ(read.position_sigma_m, written.position_sigma_m);
  EXPECT_EQ(read.correction_scale, written.correction_scale);
  EXPECT_EQ(read.correction_rotation_deg, written.correction_rotation_deg);
  EXPECT_EQ(read.correction_translation_m, written.correction_translation_m);
}

TEST(MapPlacementFile, NamesTheLineAndKeyOfABadValue) {
  const testing::TempFolder temp("map-placement-bad");
  const auto file = temp / "map_placement.yaml";
  writeMapPlacement(file, example());
  std::string text;
  {
    std::ifstream in(file);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string::size_type at = text.find("attitude: assumed");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 17, "attitude: guessed");
  std::ofstream(file) << text;
  try {
    readMapPlacement(file);
    FAIL() << "a bad attitude value was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("line 3, key attitude: expected measured or assumed, got 'guessed'"),
              std::string::npos)
        << error.what();
  }
}

TEST(MapPlacementFile, WarnsOnlyAboveOnePercent) {
  MapPlacement p = example();
  EXPECT_EQ(scaleWarning(p),
            "the map's scale is known to 1.31 % only (1-sigma, from 12 INS fixes without attitude): "
            "every length measured on the map carries that uncertainty; a longer track or a change "
            "of depth, or INS attitude, would tighten it");
  p.scale_sigma = 0.0099;
  EXPECT_EQ(scaleWarning(p), "");
}

}  // namespace
}  // namespace hsmap
