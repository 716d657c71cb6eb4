#pragma once
// Survey: a survey folder (docs/SURVEY_FORMAT.md) loaded and cross-validated, ready for
// the pipelines. loadSurvey() is the one path by which real, synthetic and
// third-party surveys enter the program.
//
// loadSurvey(folder) resolves every path of survey.yaml relative to `folder`
// and checks, in this order (the first violation throws InputError naming
// the file and the line or key):
//   1. survey.yaml (survey_config.h: strict keys, types, ranges), and that
//      every file it names exists and is a regular file (else the error names
//      survey.yaml's line and key, e.g. "key rgb.frames: the file '/dev/null'
//      is a character device; expected the frame table (file,t)");
//   2. the RGB frames: frames.csv rows and that every listed image is a PNG
//      or JPEG whose header (read, not decoded) gives rgb.camera's width x
//      height, or that the video opens at that size;
//   3. the UHI cube: the ENVI header and the data file's size (EnviReader);
//      its `samples` equals uhi.camera.samples; it has one wavelength per band
//      (an error when absent: every hyperspectral product is labelled by
//      wavelength, and guessing them would mislabel the science data);
//      wavelengths are converted to nanometres (units "Nanometers", "nm" or
//      absent = nm; "Micrometers", "um" = x1000; anything else is an error);
//      with `lights`: lights.response (lamp_response_csv.h) has one row per
//      band of the cube;
//   4. uhi/lines.csv: one row per scan line of the cube, time-ordered;
//   5. nav/ins.csv: time-ordered fixes in physical ranges (at least one), no
//      impossible jump between consecutive fixes; suspicious jumps are
//      warnings naming their line (ins_jump_check.h);
//   6. time spans: the RGB span and the UHI span (recorded times + the
//      survey's time_offset_s guess) must overlap the INS span — disjoint
//      spans are an error (nothing could be geo-referenced); partial coverage
//      is allowed and reported in `warnings` (those frames/lines lie outside
//      the INS span and can only be extrapolated).
// A camera_sigma with a sigma > 0 asks for self-calibrated intrinsics, which
// this version does not do: the first of `warnings` says so (so that both
// `hsmap inspect` and `hsmap run` print it once).
// The optional truth/ folder (synthetic surveys) is detected and its
// expected files listed; its readers come with the simulator.
//
// Nothing is loaded whole that can be large: images are decoded on demand
// and the cube is streamed line by line through `cube`.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/io/envi_reader.h"
#include "core/survey/csv_table.h"
#include "core/survey/rgb_frame_source.h"
#include "core/survey/survey_config.h"

namespace hsmap {

// What the optional truth/ folder holds (docs/SURVEY_FORMAT.md "Ground truth").
struct TruthFolder {
  bool present = false;
  std::filesystem::path folder;            // <survey>/truth
  std::vector<std::string> found_files;    // expected files that exist, e.g. "rgb_poses.csv"
  std::vector<std::string> missing_files;  // expected files that do not
};

struct Survey {
  std::filesystem::path folder;
  SurveyConfig config;

  // Resolved paths (folder / what survey.yaml says).
  std::filesystem::path config_path;
  std::filesystem::path cube_header_path;
  std::filesystem::path lines_path;
  std::filesystem::path ins_path;

  RgbFrameSource rgb;
  std::unique_ptr<EnviReader> cube;    // open, validated; streams scan lines
  std::vector<double> wavelengths_nm;  // one per band, from the ENVI header
  std::vector<double> line_times;      // recorded time of scan line i (without d)
  InsTable ins;
  // With survey.yaml's `lights`: the resolved lights.response and K(λ) of
  // every band (one per band of the cube); empty paths and list without.
  std::filesystem::path lamp_response_path;
  std::vector<double> lamp_response_dn;

  // W's origin: survey.yaml's `origin`, or the first INS fix.
  GeodeticPoint origin;
  bool origin_from_config = false;

  TruthFolder truth;
  // Non-fatal findings of the checks above (e.g. partial INS coverage).
  std::vector<std::string> warnings;
};

Survey loadSurvey(const std::filesystem::path& folder);

// The files truth/ is expected to hold (docs/SURVEY_FORMAT.md).
const std::vector<std::string>& expectedTruthFiles();

}  // namespace hsmap
