#pragma once
// uhi/lamp_response.csv (docs/SURVEY_FORMAT.md, "Lamp response"): K(λ), the
// DN that one lamp alone produces in each UHI band from a white Lambertian
// target 1 m away on its axis, facing it, with no water in between (a tank
// or panel measurement). The reflectance stage divides by it.
//
//   band,dn
//   0,1830.5
//   1,2012
//   ...
//
// The CSV rules of csv_table.h apply (exact header, no quoting, errors name
// the file and line). In addition `band` counts 0, 1, 2, ... in order (one
// row per UHI band, so the row of band b is data row b) and `dn` is a finite
// number > 0 (a band the lamps do not light cannot give a reflectance).
// That there is one row per band of the cube is checked by loadSurvey,
// where the cube is known.

#include <filesystem>
#include <string_view>
#include <vector>

namespace hsmap {

// K(λ) of every band; element b is band b.
std::vector<double> readLampResponseCsv(const std::filesystem::path& file);
std::vector<double> parseLampResponseCsv(std::string_view raw, const std::filesystem::path& file);
// Throws std::invalid_argument when a DN is not finite and > 0 or the list is
// empty: hsmap never writes a table it would refuse.
void writeLampResponseCsv(const std::filesystem::path& file, const std::vector<double>& dn);

}  // namespace hsmap
