#include "pipelines/simulate/scene/terrain_preset.h"

namespace hsmap {

const char* terrainPresetName(TerrainPreset preset) {
  switch (preset) {
    case TerrainPreset::flat: return "flat";
    case TerrainPreset::low_relief: return "low-relief";
    case TerrainPreset::rugged: return "rugged";
  }
  return "unknown";
}

std::optional<TerrainPreset> parseTerrainPreset(std::string_view name) {
  for (TerrainPreset preset :
       {TerrainPreset::flat, TerrainPreset::low_relief, TerrainPreset::rugged}) {
    if (name == terrainPresetName(preset)) return preset;
  }
  return std::nullopt;
}

}  // namespace hsmap
