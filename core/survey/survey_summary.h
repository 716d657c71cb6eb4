#pragma once
// SurveySummary: what `hsmap inspect` reports about a loaded survey — its
// sensors (with the camera sigmas and lamps when survey.yaml gives them), the
// time span, rate and gaps of each stream, band wavelengths, origin and
// ground truth — as data (for tests and reports) and as text.
//
// Rates and gaps: a stream's nominal step is the median of its time steps
// (robust to the gaps themselves); a step longer than 1.5x that median is a
// gap (a dropped frame at constant rate is a step of 2x). The rate printed is
// 1 / median step.

#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "core/survey/survey.h"

namespace hsmap {

// A step longer than 1.5x the median, between entries index-1 and index
// (0-based: frame, scan line or fix number).
struct TimeGap {
  std::size_t index = 0;
  double t_before = 0.0;
  double t_after = 0.0;
};

struct StreamTiming {
  std::size_t count = 0;
  double first_t = 0.0;
  double last_t = 0.0;
  double median_step_s = 0.0;  // 0 with fewer than two time stamps
  double rate_hz = 0.0;        // 1 / median_step_s, 0 when undefined
  std::size_t gap_count = 0;
  std::vector<TimeGap> first_gaps;  // the first few gaps (at most max_listed_gaps)
};

// Times must be strictly increasing (as every survey reader guarantees).
StreamTiming analyzeTimeStamps(const std::vector<double>& times, std::size_t max_listed_gaps = 5);

struct SurveySummary {
  std::string name;
  std::filesystem::path folder;

  std::string rgb_source;  // "frames.csv" or "video", with its path
  PinholeRadtanParameters rgb_camera;
  StreamTiming rgb;

  std::optional<PinholeRadtanSigma> rgb_camera_sigma;  // survey.yaml's rgb.camera_sigma, when given

  PushbroomParameters uhi_camera;
  std::optional<PushbroomSigma> uhi_camera_sigma;
  int uhi_samples = 0;
  int uhi_lines = 0;
  int uhi_bands = 0;
  std::string uhi_data_type;   // e.g. "uint16"
  std::string uhi_interleave;  // "bil", "bip" or "bsq"
  double wavelength_min_nm = 0.0;
  double wavelength_max_nm = 0.0;
  double uhi_time_offset_s = 0.0;
  StreamTiming uhi;  // recorded scan-line times

  bool ins_has_attitude = false;
  StreamTiming ins;

  // survey.yaml's lights, when given, with K(λ)'s band count and range.
  std::optional<LightsConfig> lights;
  std::filesystem::path lamp_response_path;
  std::size_t lamp_response_bands = 0;
  double lamp_response_min_dn = 0.0;
  double lamp_response_max_dn = 0.0;

  GeodeticPoint origin;
  bool origin_from_config = false;
  TruthFolder truth;
  std::vector<std::string> warnings;
};

// Reads every RGB frame file once (rgb_frame_check.h): a damaged frame is
// one of the warnings.
SurveySummary summarizeSurvey(const Survey& survey);

// Human-readable multi-line report.
void printSurveySummary(std::ostream& out, const SurveySummary& summary);

}  // namespace hsmap
