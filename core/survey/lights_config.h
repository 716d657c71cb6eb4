#pragma once
// LightsConfig: survey.yaml's optional `lights` block (docs/SURVEY_FORMAT.md):
// the vehicle's lamps, all of one make, and the file that gives their
// spectral response K(λ) (lamp_response_csv.h). Reflectance needs them: the
// DN a seabed point returns is its reflectance times the light the lamps put
// on it, so without the lamps' geometry and response only radiance products
// can be made.
//
//   lights:
//     response: <path>          required: uhi/lamp_response.csv (band,dn)
//     lamps:                    required: a non-empty list, one map per lamp
//       - position_m: [x, y, z] required: lamp centre in C (metres), each in [-100, 100]
//         axis: [x, y, z]       required: beam axis in C, a unit vector
//
// The axis follows the quaternion rule of survey_config.h: a norm within
// 1e-3 of 1 is normalised (hand-typed values such as [0, 0.7071, 0.7071]),
// further off (or the zero vector) is an error; a vector already of unit
// norm to double precision is kept bit-exactly, so that writing and reading
// again is an identity. The beam's shape is not given: the program
// estimates it from the survey.

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "core/survey/strict_yaml_map.h"

namespace hsmap {

struct LampConfig {
  Eigen::Vector3d p_C = Eigen::Vector3d::Zero();            // lamp centre in C, metres
  Eigen::Vector3d axis_C = Eigen::Vector3d::UnitZ();        // beam axis in C, unit norm
};

struct LightsConfig {
  std::filesystem::path response;  // the band,dn table, relative to the survey folder
  std::vector<LampConfig> lamps;   // at least one
};

// Reads the `lights` map (built by the caller with the keys `response` and
// `lamps` allowed). Throws InputError at the dotted key, e.g.
// "line 40, key lights.lamps[1].axis: expected a unit vector ...".
LightsConfig readLightsConfig(const StrictYamlMap& lights);

// Emits the value of the `lights` key: `response`, then `lamps` as a block
// list of flow maps.
void emitLightsConfig(YAML::Emitter& out, const LightsConfig& lights);

}  // namespace hsmap
