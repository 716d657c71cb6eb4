#include "pipelines/simulate/scene/terrain_preset.h"

#include <gtest/gtest.h>

namespace hsmap {
namespace {

TEST(TerrainPreset, NamesAreTheCliSpellings) {
  EXPECT_STREQ(terrainPresetName(TerrainPreset::flat), "flat");
  EXPECT_STREQ(terrainPresetName(TerrainPreset::low_relief), "low-relief");
  EXPECT_STREQ(terrainPresetName(TerrainPreset::rugged), "rugged");
}

TEST(TerrainPreset, ParsesEveryNameBack) {
  for (TerrainPreset preset :
       {TerrainPreset::flat, TerrainPreset::low_relief, TerrainPreset::rugged}) {
    EXPECT_EQ(parseTerrainPreset(terrainPresetName(preset)), preset);
  }
}

TEST(TerrainPreset, RejectsNearMisses) {
  for (const char* name : {"", "Flat", "low_relief", "lowrelief", "rugged ", " rugged", "rough"}) {
    EXPECT_EQ(parseTerrainPreset(name), std::nullopt) << "'" << name << "'";
  }
}

}  // namespace
}  // namespace hsmap
