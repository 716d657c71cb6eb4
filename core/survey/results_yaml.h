#pragma once
// Reading helpers shared by the YAML files of a results folder (run.yaml,
// calibration.yaml): values that StrictYamlMap does not cover because only
// results have them — `null` for "not estimated", the variant name, lists of
// texts. Same error style: InputError naming the file, line and dotted key.

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/survey/strict_yaml_map.h"

namespace hsmap {

// `map.key`, which must be one of runVariants() (run_variants.h).
std::string readRunVariant(const StrictYamlMap& map, const std::string& key);

// A required key whose value (`value`, the node at map.key) is null, or a
// list of 3 finite numbers >= 0 / a finite number >= 0.
std::optional<Eigen::Vector3d> readNullableSigmas(const StrictYamlMap& map,
                                                  const YAML::Node& value, const std::string& key);
std::optional<double> readNullableSigma(const StrictYamlMap& map, const YAML::Node& value,
                                        const std::string& key);

// A required number >= 0 (times, memory).
double readNonNegativeNumber(const StrictYamlMap& map, const std::string& key);

// A required list (possibly empty) of printable texts.
std::vector<std::string> readTextList(const StrictYamlMap& map, const YAML::Node& value,
                                      const std::string& key);

// The line and key of element `index` of the list at map.key, for messages:
// "line 9, key warnings[1]".
std::string listElementWhere(const StrictYamlMap& map, const YAML::Node& element,
                             const std::string& key, std::size_t index);

// `text` is printable (no control characters) and at most
// StrictYamlMap::kMaxTextValueBytes long; otherwise throws InputError at `where`.
void requirePrintableText(const std::filesystem::path& file, const std::string& where,
                          const std::string& text);

}  // namespace hsmap
