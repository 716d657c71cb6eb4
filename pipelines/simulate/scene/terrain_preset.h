#pragma once
// TerrainPreset: the three seabed reliefs the simulator can build, and their
// names as the CLI and survey metadata spell them.
//
//   flat        a plane with millimetre-to-centimetre roughness (< 5 cm peak to peak)
//   low-relief  gentle undulation of about 0.2-0.4 m over metres, plus roughness
//   rugged      a steep scarp and a ridge across the track (1 m and more of relief),
//               rocky crests and boulders, some of them overhanging
//
// seabed_height_field.h and seabed_scene.h define what each preset contains.

#include <optional>
#include <string_view>

namespace hsmap {

enum class TerrainPreset { flat, low_relief, rugged };

// "flat", "low-relief" or "rugged".
const char* terrainPresetName(TerrainPreset preset);

// The preset whose name is exactly `name` (as terrainPresetName spells it),
// std::nullopt for anything else.
std::optional<TerrainPreset> parseTerrainPreset(std::string_view name);

}  // namespace hsmap
