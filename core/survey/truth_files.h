#pragma once
// The text files of a simulated survey's ground truth (docs/SURVEY_FORMAT.md,
// "truth/"), read strictly and written so that they read back bit-identically:
//
//   truth/rgb_poses.csv     t,x,y,z,qw,qx,qy,qz        T_W_C of every RGB frame
//   truth/uhi_poses.csv     line,t,x,y,z,qw,qx,qy,qz   T_W_U of every scan line at its
//                                                      true time (recorded time + d)
//   truth/calibration.yaml  format: hsmap-truth/1 (below)
//
// The two CSV files are the pose tables of pose_tables.h (the same reader and
// writer as a run's trajectory/ files): exact header, cell count, finite
// numbers, strictly increasing t, unit quaternions (norm within 1e-6),
// uhi_poses.csv numbering its rows 0, 1, 2, ... like uhi/lines.csv; errors
// name the file and line. TruthPose / TruthLinePose keep their own field names
// (T_W_X, T_W_U) for the code that reads truth.
//
// calibration.yaml (strict_yaml_map.h rules: unknown, duplicated or missing
// keys are errors naming the line and key):
//   format: hsmap-truth/1
//   T_C_U: {rotation_wxyz: [w, x, y, z], translation_m: [x, y, z]}
//   time_offset_s: <s>                      d: true UHI time = recorded time + d
//   T_B_C: {rotation_wxyz: [...], translation_m: [...]}
//   rgb_camera: {model: pinhole-radtan, ...}  keys as survey.yaml's rgb.camera
//   uhi_camera: {model: pushbroom, ...}       keys as survey.yaml's uhi.camera
//   water_attenuation_per_m: [c_1, ..., c_bands]  Beer-Lambert coefficient per
//                                                 UHI band (1/m), each finite and >= 0
//   backscatter_dn: [b_1, ..., b_bands]        optional: the additive backscatter
//                                                 per band (DN, >= 0), as many as
//                                                 water_attenuation_per_m; absent: zeros
// The band count cannot be checked here (it is the cube's); the list must be
// non-empty. Rotations follow survey_config.h's rule (norm within 1e-3 of 1).
//
// Readers throw InputError, e.g.
//   "truth/uhi_poses.csv:line 4: columns qw,qx,qy,qz: expected a unit quaternion
//    (norm within 1e-06 of 1), got norm 1.5".
// Writers write atomically (AtomicFile), numbers in shortest round-trip form,
// and throw std::invalid_argument for data their reader would refuse
// (non-finite values, times not increasing, non-unit quaternions, lines not
// counting from 0), so hsmap never writes a truth file it cannot read.

#include <filesystem>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/se3.h"
#include "core/survey/pose_tables.h"
#include "core/survey/survey_config.h"

namespace hsmap {

// A pose of sensor X (the RGB camera C, in rgb_poses.csv) at time t.
struct TruthPose {
  double t = 0.0;
  SE3d T_W_X;
};

// The pose of the UHI frame U for scan line `line` at its true time t.
struct TruthLinePose {
  long long line = 0;
  double t = 0.0;
  SE3d T_W_U;
};

struct TruthCalibration {
  static constexpr const char* kFormat = "hsmap-truth/1";
  RigidTransformConfig T_C_U;
  double time_offset_s = 0.0;
  RigidTransformConfig T_B_C;
  PinholeRadtanParameters rgb_camera;
  PushbroomParameters uhi_camera;
  std::vector<double> water_attenuation_per_m;
  std::vector<double> backscatter_dn;  // empty: absent (zeros)
};

std::vector<TruthPose> readTruthPoses(const std::filesystem::path& file);
void writeTruthPoses(const std::filesystem::path& file, const std::vector<TruthPose>& poses);

std::vector<TruthLinePose> readTruthLinePoses(const std::filesystem::path& file);
void writeTruthLinePoses(const std::filesystem::path& file,
                         const std::vector<TruthLinePose>& poses);

TruthCalibration readTruthCalibration(const std::filesystem::path& file);
void writeTruthCalibration(const std::filesystem::path& file, const TruthCalibration& calibration);

}  // namespace hsmap
