#pragma once
// The built-in sample survey: a small, deterministic survey folder in the
// docs/SURVEY_FORMAT.md format, written entirely through the project's writers, so that
// `hsmap inspect`, the tests and the demo have data without any download.
//
// It is a sample, not a simulation: the RGB frames are a blurred random
// texture sliding north under a down-looking camera, the UHI lines sample the
// same texture across-track with two mixed reflectance spectra, and the INS
// moves north at 0.5 m/s. It has no ground truth and no physically exact
// geometry; the simulator (with truth/) replaces it for evaluation.
//
// Contents (about 3 s of survey starting at t = 36000 s):
//   survey.yaml      written by writeSurveyConfig, with an origin
//   rgb/frames.csv   75 frames at 25 Hz, rgb/frame_NNNN.png, 160x120 BGR
//   uhi/cube.hdr/.raw  90 lines x 64 samples x 16 bands (400-800 nm), uint16, bil
//   uhi/lines.csv    90 lines at 30 Hz
//   nav/ins.csv      6 fixes at 1 Hz with attitude, covering both streams
// Two calls write byte-identical files.

#include <filesystem>
#include <string>
#include <vector>

namespace hsmap {

struct SampleSurveyContents {
  std::filesystem::path folder;
  int rgb_frames = 0;
  int rgb_width = 0;
  int rgb_height = 0;
  int uhi_lines = 0;
  int uhi_samples = 0;
  int uhi_bands = 0;
  int ins_fixes = 0;
  double duration_s = 0.0;
  std::vector<std::string> files;  // relative to `folder`, in writing order
};

// Writes the sample survey to `folder`. Everything is first written to the
// sibling folder "<folder>.partial" and renamed to `folder` at the end, so an
// interrupted call never leaves a half-written survey under the final name.
// An existing `folder` is replaced as a whole (callers decide whether that is
// allowed: `hsmap sample` refuses a non-empty folder without --force).
SampleSurveyContents writeSampleSurvey(const std::filesystem::path& folder);

}  // namespace hsmap
