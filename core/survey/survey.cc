#include "core/survey/survey.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/io/envi_header.h"
#include "core/survey/ins_jump_check.h"
#include "core/survey/lamp_response_csv.h"
#include "core/survey/number_text.h"
#include "core/util/regular_file.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"

namespace hsmap {
namespace {

std::string seconds(double t) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.3f", t);
  return text;
}

std::string spanText(double first, double last) {
  std::string text = "[";
  text += seconds(first);
  text += ", ";
  text += seconds(last);
  text += "] s";
  return text;
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

RgbFrameSource openRgb(const Survey& survey) {
  const RgbConfig& rgb = survey.config.rgb;
  RgbFrameSource source = rgb.video
                              ? RgbFrameSource::fromVideo(survey.folder / rgb.video->video,
                                                          rgb.video->start_time, rgb.video->fps)
                              : RgbFrameSource::fromFrameList(survey.folder / rgb.frames);
  const cv::Size expected(rgb.camera.width, rgb.camera.height);
  if (const auto other = source.findFrameOfOtherSize(expected)) {
    const cv::Size size = source.frameSize(*other);
    const std::string detail = std::to_string(size.width) + "x" + std::to_string(size.height) +
                               " pixels but " + survey.config_path.string() +
                               " gives rgb.camera width " + std::to_string(rgb.camera.width) +
                               ", height " + std::to_string(rgb.camera.height);
    if (source.isVideo()) throw InputError(source.sourcePath(), "", "frames are " + detail);
    throw InputError(source.sourcePath(), InputError::atLine(source.frameLine(*other)),
                     "column 'file': image " +
                         quoteForMessage(source.framePath(*other).filename().string()) + " is " +
                         detail);
  }
  return source;
}

std::vector<double> wavelengthsInNm(const EnviHeader& header, const std::filesystem::path& hdr) {
  if (header.wavelength.empty()) {
    throw InputError(hdr, InputError::atKey("wavelength"),
                     "missing: hsmap needs the wavelength of each of the " +
                         std::to_string(header.bands) + " bands to label its products");
  }
  if (static_cast<int>(header.wavelength.size()) != header.bands) {
    throw InputError(hdr, InputError::atKey("wavelength"),
                     "expected " + std::to_string(header.bands) + " values (one per band), got " +
                         std::to_string(header.wavelength.size()));
  }
  const std::string units = lowercase(header.wavelength_units);
  double scale = 0.0;
  if (units.empty() || units == "nanometers" || units == "nanometres" || units == "nm") {
    scale = 1.0;
  } else if (units == "micrometers" || units == "micrometres" || units == "um" ||
             units == "microns") {
    scale = 1000.0;
  } else {
    throw InputError(
        hdr, InputError::atKey("wavelength units"),
        "unsupported units " + quoteForMessage(header.wavelength_units) + "; expected Nanometers or Micrometers");
  }
  std::vector<double> nm;
  nm.reserve(header.wavelength.size());
  for (std::size_t b = 0; b < header.wavelength.size(); ++b) {
    const double value = header.wavelength[b] * scale;
    if (!std::isfinite(value) || !(value > 0.0)) {
      throw InputError(hdr, InputError::atKey("wavelength"),
                       "expected positive finite wavelengths, got " +
                           formatDouble(header.wavelength[b]) + " for band " +
                           std::to_string(b + 1));
    }
    nm.push_back(value);
  }
  return nm;
}

// A table with one row per item of the cube (scan line, band) against the
// cube's count: the first row too many, or the end of a table too short,
// named at its line (header on line 1, item i on line i + 2).
void checkRowsPerCubeItem(const std::filesystem::path& table, std::size_t rows, std::size_t items,
                          const std::filesystem::path& cube_header, const std::string& item,
                          const std::string& items_word, const std::string& per) {
  if (rows == items) return;
  const std::string cube_text = "the cube " + cube_header.string() + " has " + std::to_string(items) + " " + items_word;
  if (rows > items) {
    throw InputError(table, InputError::atLine(static_cast<long long>(items) + 2),
                     "row for " + item + " " + std::to_string(items) + ", but " + cube_text + "; expected one row per " +
                         per + " (" + std::to_string(rows) + " rows given)");
  }
  throw InputError(table, InputError::atLine(static_cast<long long>(rows) + 1),
                   "the table ends at " + item + " " + std::to_string(rows - 1) + " (" + std::to_string(rows) +
                       " rows), but " + cube_text + "; expected one row per " + per);
}

void checkLineCount(const Survey& survey) {
  checkRowsPerCubeItem(survey.lines_path, survey.line_times.size(),
                       static_cast<std::size_t>(survey.cube->header().lines), survey.cube_header_path, "scan line",
                       "lines", "scan line");
}

// lights.response gives K(λ) per band: a table for another camera (or with a
// band missing) would silently scale the reflectance of the wrong bands.
void checkLampResponseBandCount(const Survey& survey) {
  checkRowsPerCubeItem(survey.lamp_response_path, survey.lamp_response_dn.size(),
                       static_cast<std::size_t>(survey.cube->header().bands), survey.cube_header_path, "band",
                       "bands", "UHI band");
}

// survey.yaml asks for self-calibrated intrinsics (a camera_sigma > 0):
// said once, where the survey's warnings are, what each camera gets. The
// UHI's are estimated by the `joint` variant only (docs/JOINT.md); the RGB
// camera's by the geo-referencing bundle adjustment of `sequential` and
// `joint` (docs/GEOREF.md).
std::vector<std::string> intrinsicsWarnings(const SurveyConfig& config) {
  std::vector<std::string> warnings;
  if (config.rgb.camera_sigma && config.rgb.camera_sigma->asksForCalibration()) {
    warnings.push_back(
        "survey.yaml gives rgb.camera_sigma (self-calibrated intrinsics): the sequential and joint "
        "variants estimate them in the geo-referencing bundle adjustment; planar and stacked use rgb.camera "
        "as given");
  }
  if (config.uhi.camera_sigma && config.uhi.camera_sigma->asksForCalibration()) {
    warnings.push_back(
        "survey.yaml gives uhi.camera_sigma (self-calibrated intrinsics): the joint variant estimates "
        "them; the other variants use uhi.camera as given");
  }
  return warnings;
}

// Checks that [first, last] of a stream overlaps the INS span; records a
// warning when part of it lies outside.
void checkCoverage(Survey& survey, const std::string& stream, const std::filesystem::path& file,
                   double first, double last) {
  const double ins_first = survey.ins.fixes.front().t;
  const double ins_last = survey.ins.fixes.back().t;
  if (last < ins_first || first > ins_last) {
    throw InputError(file, "",
                     "the " + stream + " time span " + spanText(first, last) +
                         " does not overlap the INS time span " + spanText(ins_first, ins_last) +
                         " of " + survey.ins_path.string() +
                         ": nothing could be geo-referenced (are both on the same clock?)");
  }
  if (first < ins_first || last > ins_last) {
    std::string text = "the " + stream + " time span " + spanText(first, last) +
                       " is not fully covered by the INS span " + spanText(ins_first, ins_last) +
                       ":";
    if (first < ins_first)
      text += " " + seconds(ins_first - first).append(" s before the first fix");
    if (first < ins_first && last > ins_last) text += " and";
    if (last > ins_last) text += " " + seconds(last - ins_last).append(" s after the last fix");
    survey.warnings.push_back(text + " (poses there are extrapolated)");
  }
}

// A file named by survey.yaml that is missing or is not a regular file (a
// FIFO, /dev/null) is reported at the key that named it: the user's mistake
// is in survey.yaml, and the file's own name may not tell which key it was.
void checkReferencedFile(const Survey& survey, const std::string& key,
                         const std::filesystem::path& file, const std::string& expected) {
  const auto why = whyNotRegularFile(file);
  if (!why) return;
  const auto line = survey.config.file_key_lines.find(key);
  std::string where = InputError::atKey(key);
  if (line != survey.config.file_key_lines.end()) where = InputError::atLine(line->second) + ", " + where;
  const std::string found = *why == "not found" ? "not found" : "is " + *why;
  throw InputError(survey.config_path, where,
                   "the file " + quoteForMessage(file.string(), 120) + " " + found +
                       "; expected " + expected);
}

void checkReferencedFiles(const Survey& survey) {
  const SurveyConfig& config = survey.config;
  if (config.rgb.video) {
    checkReferencedFile(survey, "rgb.video", survey.folder / config.rgb.video->video,
                        "a video file");
  } else {
    checkReferencedFile(survey, "rgb.frames", survey.folder / config.rgb.frames,
                        "the frame table (file,t)");
  }
  checkReferencedFile(survey, "uhi.cube", survey.cube_header_path, "an ENVI header (.hdr)");
  checkReferencedFile(survey, "uhi.lines", survey.lines_path, "the scan-line table (line,t)");
  checkReferencedFile(survey, "ins.file", survey.ins_path, "the INS table (t,lat,lon,depth...)");
  if (config.lights) {
    checkReferencedFile(survey, "lights.response", survey.lamp_response_path,
                        "the lamp response table (band,dn)");
  }
}

TruthFolder detectTruth(const std::filesystem::path& folder) {
  TruthFolder truth;
  truth.folder = folder / "truth";
  std::error_code error;
  truth.present = std::filesystem::is_directory(truth.folder, error);
  if (!truth.present) return truth;
  for (const auto& name : expectedTruthFiles()) {
    (std::filesystem::is_regular_file(truth.folder / name, error) ? truth.found_files
                                                                  : truth.missing_files)
        .push_back(name);
  }
  return truth;
}

}  // namespace

const std::vector<std::string>& expectedTruthFiles() {
  static const std::vector<std::string> files = {"rgb_poses.csv",    "uhi_poses.csv",
                                                 "calibration.yaml", "scene.ply",
                                                 "reflectance.hdr",  "reflectance.raw"};
  return files;
}

Survey loadSurvey(const std::filesystem::path& folder) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) {
    throw InputError(folder, "", "survey folder not found (expected a folder holding survey.yaml)");
  }
  Survey survey;
  survey.folder = folder;
  survey.config_path = folder / "survey.yaml";
  survey.config = readSurveyConfig(survey.config_path);
  const SurveyConfig& config = survey.config;
  survey.cube_header_path = folder / config.uhi.cube;
  survey.lines_path = folder / config.uhi.lines;
  survey.ins_path = folder / config.ins.file;
  if (config.lights) survey.lamp_response_path = folder / config.lights->response;
  checkReferencedFiles(survey);
  for (std::string& warning : intrinsicsWarnings(config)) survey.warnings.push_back(std::move(warning));

  survey.rgb = openRgb(survey);

  survey.cube = std::make_unique<EnviReader>(survey.cube_header_path);
  const EnviHeader& header = survey.cube->header();
  if (header.samples != config.uhi.camera.samples) {
    throw InputError(survey.cube_header_path, InputError::atKey("samples"),
                     "the cube has " + std::to_string(header.samples) + " samples per line but " +
                         survey.config_path.string() + " gives uhi.camera.samples " +
                         std::to_string(config.uhi.camera.samples) +
                         "; the camera model must describe every pixel of a line");
  }
  survey.wavelengths_nm = wavelengthsInNm(header, survey.cube_header_path);
  if (config.lights) {
    survey.lamp_response_dn = readLampResponseCsv(survey.lamp_response_path);
    checkLampResponseBandCount(survey);
  }

  survey.line_times = readLinesCsv(survey.lines_path);
  checkLineCount(survey);

  survey.ins = readInsCsv(survey.ins_path);
  for (auto& warning : checkInsJumps(survey.ins, survey.ins_path, config.ins.sigma_horizontal_m,
                                     config.ins.sigma_depth_m)) {
    survey.warnings.push_back(std::move(warning));
  }

  checkCoverage(survey, "RGB", survey.rgb.sourcePath(), survey.rgb.times().front(),
                survey.rgb.times().back());
  checkCoverage(survey, "UHI", survey.lines_path,
                survey.line_times.front() + config.uhi.time_offset_s,
                survey.line_times.back() + config.uhi.time_offset_s);

  if (config.origin) {
    survey.origin = *config.origin;
    survey.origin_from_config = true;
  } else {
    const InsFix& first = survey.ins.fixes.front();
    survey.origin = {first.lat_deg, first.lon_deg, first.depth_m};
  }
  survey.truth = detectTruth(folder);
  if (survey.truth.present && !config.origin) {
    survey.warnings.push_back(
        "truth/ is present but survey.yaml gives no origin; truth is expressed in the W of a "
        "stated origin (docs/SURVEY_FORMAT.md)");
  }
  return survey;
}

}  // namespace hsmap
