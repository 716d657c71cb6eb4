#include "core/survey/survey_summary.h"

#include <algorithm>
#include <cstdio>
#include <ostream>

#include "core/io/envi_header.h"
#include "core/survey/number_text.h"
#include "core/survey/rgb_frame_check.h"
#include "core/util/median.h"
#include "core/util/message_text.h"

namespace hsmap {
namespace {

void printStream(std::ostream& out, const char* label, const char* unit, const StreamTiming& s) {
  out << "  " << label << ": " << s.count << " " << unit << ", t = [" << fixedDecimals(s.first_t, 6) << ", "
      << fixedDecimals(s.last_t, 6) << "] s (" << fixedDecimals(s.last_t - s.first_t, 3) << " s)";
  if (s.count >= 2) out << ", " << fixedDecimals(s.rate_hz, 3) << " Hz";
  out << "\n";
  if (s.gap_count == 0) {
    out << "    gaps: none (no step longer than 1.5x the median " << fixedDecimals(s.median_step_s, 6)
        << " s)\n";
    return;
  }
  out << "    gaps: " << s.gap_count << " step(s) longer than 1.5x the median "
      << fixedDecimals(s.median_step_s, 6) << " s";
  out << (s.gap_count > s.first_gaps.size() ? "; the first:\n" : ":\n");
  for (const TimeGap& gap : s.first_gaps) {
    out << "      " << fixedDecimals(gap.t_before, 6) << " -> " << fixedDecimals(gap.t_after, 6) << " s (step "
        << fixedDecimals(gap.t_after - gap.t_before, 6) << " s, before entry " << gap.index << ")\n";
  }
}

std::string vectorText(const Eigen::Vector3d& v, int decimals) {
  std::string text = "[";
  for (int i = 0; i < 3; ++i) {
    if (i > 0) text += ", ";
    text += fixedDecimals(v[i], decimals);
  }
  return text + "]";
}

template <std::size_t N>
std::string distortionText(const std::array<double, N>& values) {
  std::string text = "[";
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) text += ", ";
    text += formatDouble(values[i]);
  }
  return text + "]";
}

// The intrinsics' sigmas are read but not used yet: the line says so, next
// to the values, and the survey's warnings say it once more.
constexpr const char* kEstimatedByGeoref = " (intrinsics estimated by the geo-referencing bundle adjustment)";
constexpr const char* kEstimatedByJoint = " (intrinsics estimated by the joint variant)";

void printRgbSigma(std::ostream& out, const PinholeRadtanSigma& sigma) {
  out << "       camera_sigma: fx " << fixedDecimals(sigma.fx, 2) << ", fy " << fixedDecimals(sigma.fy, 2)
      << ", cx " << fixedDecimals(sigma.cx, 2) << ", cy " << fixedDecimals(sigma.cy, 2)
      << ", distortion " << distortionText(sigma.distortion) << kEstimatedByGeoref << "\n";
}

void printUhiSigma(std::ostream& out, const PushbroomSigma& sigma) {
  out << "       camera_sigma: f " << fixedDecimals(sigma.f, 2) << ", cx " << fixedDecimals(sigma.cx, 2)
      << ", distortion " << distortionText(sigma.distortion) << kEstimatedByJoint << "\n";
}

void printLights(std::ostream& out, const SurveySummary& s) {
  const std::size_t lamps = s.lights->lamps.size();
  out << "  lights: " << lamps << (lamps == 1 ? " lamp" : " lamps") << "; response "
      << s.lamp_response_path.string() << ": " << s.lamp_response_bands << " bands, DN "
      << fixedDecimals(s.lamp_response_min_dn, 1) << " - " << fixedDecimals(s.lamp_response_max_dn, 1)
      << "\n";
  for (std::size_t i = 0; i < s.lights->lamps.size(); ++i) {
    const LampConfig& lamp = s.lights->lamps[i];
    out << "    lamp " << i << ": position " << vectorText(lamp.p_C, 3) << " m, axis "
        << vectorText(lamp.axis_C, 3) << " (in C)\n";
  }
}

}  // namespace

StreamTiming analyzeTimeStamps(const std::vector<double>& times, std::size_t max_listed_gaps) {
  StreamTiming timing;
  timing.count = times.size();
  if (times.empty()) return timing;
  timing.first_t = times.front();
  timing.last_t = times.back();
  if (times.size() < 2) return timing;
  std::vector<double> steps(times.size() - 1);
  for (std::size_t i = 1; i < times.size(); ++i) steps[i - 1] = times[i] - times[i - 1];
  timing.median_step_s = median(steps);
  timing.rate_hz = timing.median_step_s > 0.0 ? 1.0 / timing.median_step_s : 0.0;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (steps[i] > 1.5 * timing.median_step_s) {
      ++timing.gap_count;
      if (timing.first_gaps.size() < max_listed_gaps) {
        timing.first_gaps.push_back({i + 1, times[i], times[i + 1]});
      }
    }
  }
  return timing;
}

SurveySummary summarizeSurvey(const Survey& survey) {
  SurveySummary summary;
  const SurveyConfig& config = survey.config;
  summary.name = config.name;
  summary.folder = survey.folder;
  summary.rgb_source =
      (survey.rgb.isVideo() ? "video " : "image list ") + survey.rgb.sourcePath().string();
  summary.rgb_camera = config.rgb.camera;
  summary.rgb_camera_sigma = config.rgb.camera_sigma;
  summary.rgb = analyzeTimeStamps(survey.rgb.times());

  const EnviHeader& header = survey.cube->header();
  summary.uhi_camera = config.uhi.camera;
  summary.uhi_camera_sigma = config.uhi.camera_sigma;
  summary.uhi_samples = header.samples;
  summary.uhi_lines = header.lines;
  summary.uhi_bands = header.bands;
  summary.uhi_data_type = toString(header.data_type);
  summary.uhi_interleave = toString(header.interleave);
  summary.wavelength_min_nm =
      *std::min_element(survey.wavelengths_nm.begin(), survey.wavelengths_nm.end());
  summary.wavelength_max_nm =
      *std::max_element(survey.wavelengths_nm.begin(), survey.wavelengths_nm.end());
  summary.uhi_time_offset_s = config.uhi.time_offset_s;
  summary.uhi = analyzeTimeStamps(survey.line_times);

  summary.ins_has_attitude = survey.ins.has_attitude;
  std::vector<double> ins_times;
  ins_times.reserve(survey.ins.fixes.size());
  for (const InsFix& fix : survey.ins.fixes) ins_times.push_back(fix.t);
  summary.ins = analyzeTimeStamps(ins_times);

  summary.lights = config.lights;
  if (config.lights) {
    const std::vector<double>& dn = survey.lamp_response_dn;
    summary.lamp_response_path = survey.lamp_response_path;
    summary.lamp_response_bands = dn.size();
    if (!dn.empty()) {
      summary.lamp_response_min_dn = *std::min_element(dn.begin(), dn.end());
      summary.lamp_response_max_dn = *std::max_element(dn.begin(), dn.end());
    }
  }

  summary.origin = survey.origin;
  summary.origin_from_config = survey.origin_from_config;
  summary.truth = survey.truth;
  summary.warnings = survey.warnings;
  for (std::string& warning : checkRgbFramesWhole(survey.rgb)) summary.warnings.push_back(std::move(warning));
  return summary;
}

void printSurveySummary(std::ostream& out, const SurveySummary& s) {
  out << "survey '" << s.name << "' (" << s.folder.string() << "): valid\n";
  out << "sensors:\n";
  const PinholeRadtanParameters& c = s.rgb_camera;
  out << "  RGB: pinhole-radtan " << c.width << "x" << c.height << ", fx " << fixedDecimals(c.fx, 2)
      << ", fy " << fixedDecimals(c.fy, 2) << ", cx " << fixedDecimals(c.cx, 2) << ", cy " << fixedDecimals(c.cy, 2) << "; "
      << s.rgb_source << "\n";
  if (s.rgb_camera_sigma) printRgbSigma(out, *s.rgb_camera_sigma);
  out << "  UHI: pushbroom, " << s.uhi_samples << " samples x " << s.uhi_bands << " bands, "
      << s.uhi_lines << " lines, " << s.uhi_data_type << ", " << s.uhi_interleave << ", f "
      << fixedDecimals(s.uhi_camera.f, 2) << ", cx " << fixedDecimals(s.uhi_camera.cx, 2) << "\n";
  out << "       wavelengths " << fixedDecimals(s.wavelength_min_nm, 1) << " - "
      << fixedDecimals(s.wavelength_max_nm, 1) << " nm; time offset guess " << fixedDecimals(s.uhi_time_offset_s, 6)
      << " s\n";
  if (s.uhi_camera_sigma) printUhiSigma(out, *s.uhi_camera_sigma);
  out << "  INS: " << (s.ins_has_attitude ? "position and attitude" : "position only (no attitude)")
      << "\n";
  if (s.lights) printLights(out, s);
  out << "streams:\n";
  printStream(out, "RGB frames", "frames", s.rgb);
  printStream(out, "UHI lines", "lines", s.uhi);
  printStream(out, "INS fixes", "fixes", s.ins);
  out << "origin: lat " << fixedDecimals(s.origin.lat_deg, 8) << ", lon " << fixedDecimals(s.origin.lon_deg, 8)
      << ", depth " << fixedDecimals(s.origin.depth_m, 3) << " m ("
      << (s.origin_from_config ? "given in survey.yaml" : "first INS fix") << ")\n";
  if (!s.truth.present) {
    out << "truth: none\n";
  } else {
    out << "truth: present (" << s.truth.found_files.size() << " of "
        << s.truth.found_files.size() + s.truth.missing_files.size() << " expected files";
    if (!s.truth.missing_files.empty()) {
      out << "; missing:";
      for (const auto& name : s.truth.missing_files) out << " " << name;
    }
    out << ")\n";
  }
  if (s.warnings.empty()) {
    out << "warnings: none\n";
  } else {
    out << "warnings:\n";
    for (const auto& warning : s.warnings) out << "  - " << warning << "\n";
  }
}

}  // namespace hsmap
