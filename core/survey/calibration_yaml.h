#pragma once
// YAML form of calibration quantities shared by survey.yaml,
// truth/calibration.yaml and a run's calibration.yaml (docs/SURVEY_FORMAT.md): the two
// camera parameter sets (`model: pinhole-radtan`, `model: pushbroom`) and rigid
// transforms (`rotation_wxyz`, `translation_m`). Reading is strict (see
// strict_yaml_map.h and survey_config.h for the rules and ranges); writing
// produces text that reads back to identical values.

#include <yaml-cpp/yaml.h>

#include <string>

#include "core/geometry/camera_parameters.h"
#include "core/survey/strict_yaml_map.h"
#include "core/survey/survey_config.h"

namespace hsmap {

// Reads the camera map at `parent.key`. Keys: model, width, height, fx, fy,
// cx, cy, distortion (5, optional) / model, samples, f, cx, distortion (2, optional).
PinholeRadtanParameters readPinholeRadtanCamera(const StrictYamlMap& parent,
                                                const std::string& key);
PushbroomParameters readPushbroomCamera(const StrictYamlMap& parent, const std::string& key);

// Reads `rotation_wxyz` and `translation_m` from `map` (which the caller built
// with those keys allowed, plus any of its own). Quaternion rule: see survey_config.h.
RigidTransformConfig readRigidTransform(const StrictYamlMap& map);

// Emit the value of a camera map (flow style, as in docs/SURVEY_FORMAT.md) / the two
// keys of a transform into the map the emitter is currently in.
void emitPinholeRadtanCamera(YAML::Emitter& out, const PinholeRadtanParameters& camera);
void emitPushbroomCamera(YAML::Emitter& out, const PushbroomParameters& camera);
void emitRigidTransformKeys(YAML::Emitter& out, const RigidTransformConfig& transform);

// A double as its shortest round-trip YAML scalar.
void emitNumber(YAML::Emitter& out, double value);

}  // namespace hsmap
