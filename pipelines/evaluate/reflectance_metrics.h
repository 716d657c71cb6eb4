#pragma once
// The reflectance metrics of metrics.json (shared/DATASET.md, "Reflectance"):
// RUN/hyperspectral/reflectance.hdr against truth/reflectance.hdr, and the
// estimated c(λ) (RUN/radiometry/water.yaml) against truth/calibration.yaml's
// water_attenuation_per_m.
//
// Both rasters are averaged over blocks of block_m (2 cm) of the TRUE grid,
// so that millimetre registration errors at material edges do not count: for
// every truth pixel valid in every band, the produced pixel NEAREST its
// centre is looked up (the truth's W position mapped to UTM through the
// survey origin, at the registered position when the ortho metrics measured
// a registration: the 2-D similarity fitted to their patch matches, so that
// the spectra are judged and not the geo-referencing, as for ortho_sam_deg);
// a pair counts when the produced pixel has any band that is a number (the
// ortho metrics' validity). A block is valid in both when at least
// min_valid_fraction of its truth pixels form pairs; its two spectra are the
// means over its pairs, band by band, over the bands the product determined
// there (a band NaN in all its pairs, too dark to measure, is left out of
// the block's angle and of the sums, and counted).
//
//   reflectance_sam_deg         mean over valid blocks of the spectral angle (degrees)
//   reflectance_rmse            RMS over blocks and bands of (produced − true)
//   reflectance_gain_free_rmse  RMS of (g_b · produced − true) over blocks and
//                               bands, g_b the least-squares gain of band b,
//                               divided by the RMS true reflectance
//   water_attenuation_rmse_per_m  RMS over bands of (estimated − true) c(λ)
//
// Streaming: the truth is read a block row at a time, the produced rows it
// needs are cached while they are needed; memory is a few rows of each.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/geometry/geodetic_point.h"
#include "pipelines/evaluate/metric_value.h"
#include "pipelines/evaluate/ortho_metrics.h"

namespace hsmap {

struct ReflectanceMetricsOptions {
  double block_m = 0.02;
  double min_valid_fraction = 0.5;
  double reference_down_m = 0.0;  // as OrthoMetricsOptions::reference_down_m
};

struct ReflectanceMetrics {
  MetricValue reflectance_sam_deg;
  MetricValue reflectance_rmse;
  MetricValue reflectance_gain_free_rmse;
  MetricValue water_attenuation_rmse_per_m;
  std::int64_t blocks = 0;  // valid in both
  std::int64_t band_values_left_out = 0;  // block-band values the product left NaN (too dark)
  int block_pixels = 0;     // side of a block in truth pixels
  bool registered = false;

  std::string summary() const;
};

// The four metrics of a run folder: missing (saying why) when the run has no
// reflectance product or no water estimate. `matches` are the ortho metrics'
// patch matches (registration), empty: as placed. Throws InputError for
// unreadable rasters or a water estimate whose bands differ from the truth's.
ReflectanceMetrics measureRunReflectance(const std::filesystem::path& run_folder,
                                         const std::filesystem::path& truth_reflectance_hdr,
                                         const std::vector<double>& true_attenuation_per_m,
                                         const GeodeticPoint& origin, const std::vector<OrthoPatchMatch>& matches,
                                         const ReflectanceMetricsOptions& options = {});

}  // namespace hsmap
