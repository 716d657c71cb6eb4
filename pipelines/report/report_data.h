#pragma once
// ReportData: what RUN/report/index.html shows, collected from the run folder
// (and the survey it names) by the collect_*.h functions, turned into the
// page's JSON by report_json.h. Positions are in W (north, east, down, in
// metres), as in trajectory/; times on the survey's clock.
//
// A part the run folder does not have (a variant without a front-end, a run
// stopped with --until, no truth) is left empty and `notes` says what is not
// shown and why: the page then states it instead of drawing an empty plot.

#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/survey/run_calibration.h"

namespace hsmap {

struct ReportStage {
  std::string name;
  double time_s = 0.0;
  double peak_rss_mb = 0.0;
};

// A camera centre (frames, keyframes) or an INS fix in W.
struct ReportPosition {
  double t = 0.0;
  double north = 0.0, east = 0.0, down = 0.0;
};

struct ReportInsFix {
  ReportPosition position;  // the body B as the INS reports it
  long long ins_line = 0;   // line in nav/ins.csv
  bool rejected = false;    // left out by geo-referencing (georef/rejected_fixes.csv)
  std::string rejected_at;  // the step that left it out, when rejected
};

struct ReportTrackingLoss {
  long long first_frame = 0, last_frame = 0;
  double t_first = NAN, t_last = NAN;  // NaN when the frames are not in trajectory/frames.csv
  std::string reason;
};

// A histogram binned here (the page draws it): rugged has ~10^6 reprojection
// residuals, too many to embed one by one.
struct ReportHistogram {
  std::string name;         // e.g. "reprojection after geo-referencing"
  std::string unit;         // "px", "m"
  double bin_width = 0.0;   // bins [i w, (i+1) w), i = 0..counts.size()-1
  std::vector<long long> counts;
  std::vector<long long> outlier_counts;  // of counts, how many are outliers
  long long beyond = 0;           // values at or beyond counts.size() * bin_width
  long long beyond_outliers = 0;  // of those, outliers
  long long total = 0;
  double median = NAN, rms = NAN;
  double outlier_threshold = NAN;  // where the robust loss starts down-weighting (NaN: no threshold)
  std::string outlier_meaning;     // what an outlier is here, in words
  long long outliers = 0;
};

// The hyperspectral ortho-image averaged over blocks of `block_px` x
// `block_px` pixels, each band quantised to 16 bits (value = offset + scale *
// q, q = 65535 for a block without data), so that the page reads a spectrum
// wherever it is clicked without carrying the full cube.
struct ReportSpectralGrid {
  int columns = 0, rows = 0;  // blocks
  int block_px = 1;
  int image_columns = 0, image_rows = 0;  // the ortho-image's pixels
  std::vector<double> wavelengths_nm;
  std::vector<double> offsets, scales;  // per band
  std::vector<unsigned short> values;   // [(row * columns + column) * bands + band]
  std::string value_meaning;            // e.g. "radiance, as in the cube (DN)"
};

// An image for the page, already downsampled and encoded as a data: URI.
struct ReportImage {
  std::string data_uri;
  int width = 0, height = 0;       // of the encoded image
  int full_width = 0, full_height = 0;  // of the product it shows
  std::string source;              // the run folder's file it shows
};

// The mesh seen from above: an image, with where it lies in W.
struct ReportTopView {
  ReportImage image;
  double north_max = 0.0, east_min = 0.0, pixel_m = 0.0;  // upper-left corner and pixel size
};

struct ReportOrthoPatch {
  double north = 0.0, east = 0.0;                          // patch centre, in the ortho's local frame
  double displacement_north = 0.0, displacement_east = 0.0;  // m
  double response = 0.0;                                   // phase correlation peak
};

struct ReportData {
  // The survey and the run.
  std::string run_folder;
  std::string survey_name;
  std::string survey_folder;
  std::string variant;
  std::string program_version;
  std::string started_utc;
  bool run_complete = false;  // run.yaml is there (every stage asked for succeeded)
  std::vector<std::pair<std::string, std::string>> options;
  std::vector<ReportStage> stages;
  double total_time_s = NAN, peak_rss_mb = NAN;
  std::vector<std::string> warnings;  // every warning, prefixed by where it was found
  std::vector<std::string> notes;     // what the page does not show, and why

  // The trajectory.
  std::vector<ReportPosition> frames;     // trajectory/frames.csv, camera centres
  std::vector<ReportPosition> keyframes;  // the adjusted map's keyframes
  std::vector<ReportInsFix> ins_fixes;
  std::vector<ReportTrackingLoss> losses;
  std::vector<double> seabed_down;        // per frame: the mesh's surface below it (NaN: none)

  // Residuals.
  std::vector<ReportHistogram> histograms;

  // The calibration.
  std::optional<RunCalibration> calibration;
  std::string calibration_source;
  // survey.yaml's cameras, to show how far an estimated camera moved from
  // them (nullopt: the survey could not be read).
  std::optional<PushbroomParameters> survey_uhi_camera;
  std::optional<PinholeRadtanParameters> survey_rgb_camera;

  // Images and spectra.
  std::optional<ReportImage> hyperspectral_ortho;  // the quick-look
  std::optional<ReportImage> rgb_ortho;            // on the same grid
  double ortho_pixel_m = NAN;                      // of the full-size ortho-images
  std::optional<ReportTopView> mesh_top_view;
  std::optional<ReportSpectralGrid> spectra;

  // With truth (after `hsmap evaluate`).
  std::vector<std::pair<std::string, std::optional<double>>> metrics;  // metrics.json, in its order
  std::vector<ReportOrthoPatch> ortho_patches;
};

}  // namespace hsmap
