#pragma once
// SurveyConfig: the contents of a survey folder's survey.yaml (docs/SURVEY_FORMAT.md),
// read with strict validation and written back so that it reads identically.
//
// Keys, types, ranges and defaults (a key marked "optional" may be absent):
//
//   format: hsmap-survey/1                   required, exactly this text
//   name: <text>                             required, non-empty
//   rgb:
//     frames: <path>                         exactly one of `frames` or `video`
//     video: <path>                          a video file read with OpenCV;
//     start_time: <s>                          with `video` only, then required, in [-4e9, 4e9]
//     fps: <Hz>                                with `video` only, then required, in (0, 10000]
//     camera:
//       model: pinhole-radtan                required, the only RGB model
//       width, height: <px>                  required integers in [1, 65536]
//       fx, fy: <px>                         required, in (0, 1e6]
//       cx, cy: <px>                         required, in [-1e6, 1e6]
//       distortion: [k1, k2, p1, p2, k3]     optional, 5 numbers in [-1000, 1000]; default zeros
//     camera_sigma:                          optional: 1-sigma of rgb.camera (camera_sigma.h)
//       fx, fy, cx, cy: <px>                 optional, in [0, 1e6]; default 0 (held fixed)
//       distortion: [5 numbers]              optional, exactly 5, each in [0, 1000]; default zeros
//   uhi:
//     cube: <path to the ENVI .hdr>          required
//     lines: <path>                          required
//     camera:
//       model: pushbroom                     required, the only UHI model
//       samples: <px>                        required integer in [1, 1000000]
//       f: <px>                              required, in (0, 1e6]
//       cx: <px>                             required, in [-1e6, 1e6]
//       distortion: [k1, k2]                 optional, 2 numbers in [-1000, 1000]; default zeros
//     camera_sigma:                          optional: 1-sigma of uhi.camera (camera_sigma.h)
//       f, cx: <px>                          optional, in [0, 1e6]; default 0 (held fixed)
//       distortion: [2 numbers]              optional, exactly 2, each in [0, 1000]; default zeros
//     extrinsic:                             required (T_C_U, the CAD guess)
//       rotation_wxyz: [w, x, y, z]          required (see quaternions below)
//       translation_m: [x, y, z]             required, each in [-100, 100]
//       sigma_rotation_deg: <deg>            optional, in (0, 180]; default 2.0
//       sigma_translation_m: <m>             optional, in (0, 100]; default 0.05
//     time_offset_s: <s>                     optional, in [-3600, 3600]; default 0.0
//     time_offset_sigma_s: <s>               optional, in (0, 3600]; default 0.05
//   ins:
//     file: <path>                           required
//     camera_in_body:                        required (T_B_C)
//       rotation_wxyz: [w, x, y, z]          required
//       translation_m: [x, y, z]             required, each in [-100, 100]
//     sigma_horizontal_m: <m>                optional, in (0, 10000]; default 0.5
//     sigma_depth_m: <m>                     optional, in (0, 10000]; default 0.05
//     sigma_attitude_deg: [roll, pitch, heading]  optional, each in (0, 180]; default [0.05, 0.05, 0.2]
//   origin: {lat, lon, depth}                optional; all three required when given;
//                                            lat in [-90, 90], lon in [-180, 180],
//                                            depth in [-10000, 12000] (m, h = -depth).
//                                            Absent: W's origin is the first INS fix.
//   lights:                                  optional: the lamps (lights_config.h)
//     response: <path>                       required in the block: band,dn (lamp_response_csv.h)
//     lamps:                                 required in the block: a non-empty list of
//       - position_m: [x, y, z]                lamp centre in C, each in [-100, 100] m
//         axis: [x, y, z]                      beam axis in C, unit vector (rule as quaternions)
//
// The camera sigmas are read and written but this version of hsmap holds the
// intrinsics fixed (loadSurvey warns when one is > 0). The lights are read
// and validated for the reflectance stage.
//
// The sigma defaults are those of a typical survey-grade INS and of a
// CAD-drawing extrinsic (docs/SURVEY_FORMAT.md's example values): loose enough not to
// bias the estimate, tight enough to fix the gauge.
//
// Quaternions (`rotation_wxyz`) are Hamilton, given as w x y z. A quaternion
// whose norm differs from 1 by at most 1e-3 is normalised (hand-typed values
// such as 0.7071 are accepted); a larger deviation is an error, because it
// means the four numbers are not a rotation (or are in the wrong order). A
// quaternion already of unit norm to double precision is kept bit-exactly, so
// writeSurveyConfig -> readSurveyConfig is an identity.
//
// Paths are stored as written (relative to the survey folder, '/'-separated);
// loadSurvey (survey.h) resolves them.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/geodetic_point.h"
#include "core/survey/camera_sigma.h"
#include "core/survey/lights_config.h"

namespace hsmap {

// A rigid transform T_A_B as written in YAML: p_A = rotation * p_B + translation_m.
struct RigidTransformConfig {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // Hamilton, unit norm
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();
};

struct RgbVideoConfig {
  std::filesystem::path video;  // relative to the survey folder
  double start_time = 0.0;      // time of frame 0, seconds on the shared clock
  double fps = 0.0;             // frame i is at start_time + i / fps
};

struct RgbConfig {
  std::filesystem::path frames;         // frames.csv; empty when `video` is set
  std::optional<RgbVideoConfig> video;  // set instead of `frames`
  PinholeRadtanParameters camera;
  // `camera_sigma`: absent when survey.yaml has none (every intrinsic fixed).
  std::optional<PinholeRadtanSigma> camera_sigma;
};

struct UhiConfig {
  std::filesystem::path cube;   // ENVI header (.hdr)
  std::filesystem::path lines;  // lines.csv
  PushbroomParameters camera;
  std::optional<PushbroomSigma> camera_sigma;  // absent: every intrinsic fixed
  RigidTransformConfig T_C_U;  // extrinsic guess: UHI frame U in RGB camera frame C
  double sigma_rotation_deg = 2.0;
  double sigma_translation_m = 0.05;
  double time_offset_s = 0.0;  // d: true UHI time = recorded time + d (initial guess)
  double time_offset_sigma_s = 0.05;
};

struct InsConfig {
  std::filesystem::path file;  // ins.csv
  RigidTransformConfig T_B_C;  // RGB camera C in the INS body B
  double sigma_horizontal_m = 0.5;
  double sigma_depth_m = 0.05;
  std::array<double, 3> sigma_attitude_deg{0.05, 0.05, 0.2};  // roll, pitch, heading
};

struct SurveyConfig {
  static constexpr const char* kFormat = "hsmap-survey/1";
  std::string name;
  RgbConfig rgb;
  UhiConfig uhi;
  InsConfig ins;
  // The geodetic point at which W (local NED) is tangent; absent: the first INS fix.
  std::optional<GeodeticPoint> origin;
  // The lamps and their response; absent: no reflectance product can be made.
  std::optional<LightsConfig> lights;

  // The 1-based survey.yaml line of each key that names a file ("rgb.frames",
  // "rgb.video", "uhi.cube", "uhi.lines", "ins.file", "lights.response"), so that a missing or
  // non-regular file is reported at the key that named it. Empty when the
  // configuration was not read from a file.
  std::map<std::string, long long> file_key_lines;
};

// Reads and validates `path` (see the table above). Throws InputError naming
// `path`, the line and the dotted key.
SurveyConfig readSurveyConfig(const std::filesystem::path& path);
// The same on the file's content `raw`; `path` names it in errors.
SurveyConfig parseSurveyConfigText(std::string_view raw, const std::filesystem::path& path);

// Writes `config` to `path` atomically (a .partial file renamed when complete).
// Numbers are written in shortest round-trip form; optional keys are always
// written (with their values), so the file documents every setting; the
// optional blocks `camera_sigma` and `lights` are written when present (all
// their keys, zeros included).
// Throws std::invalid_argument if `config` would not pass readSurveyConfig's
// checks (e.g. both or neither of rgb.frames and rgb.video).
void writeSurveyConfig(const std::filesystem::path& path, const SurveyConfig& config);

}  // namespace hsmap
