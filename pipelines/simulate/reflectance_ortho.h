#pragma once
// The true reflectance ortho-image (truth/reflectance.hdr/.raw): for every
// pixel of the UHI's swath footprint, the reflectance at the band centres of
// the topmost scene surface below the pixel's centre (a vertical ray cast
// from above the scene), i.e. what a nadir-looking observer sees there; NaN
// outside the footprint. ENVI float32, BIL, north-up, with
//   map info = {Arbitrary, 1, 1, E, N, px, px, units=Meters}
// giving the W east/north of the upper-left corner (docs/SURVEY_FORMAT.md).
// Rows are computed in parallel and streamed to the file in order; the
// header is written last (EnviWriter), so the raster is whole or absent.
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "pipelines/simulate/render_context.h"
#include "pipelines/simulate/swath_footprint.h"

namespace hsmap {

// Reflectance of the topmost surface below (north, east) at `endmembers`'
// wavelengths (MaterialField::endmemberMatrix); std::nullopt where the
// vertical ray misses the scene.
std::optional<Eigen::VectorXf> topSurfaceReflectance(const RenderContext& context,
                                                     const Eigen::MatrixXf& endmembers,
                                                     double north_m, double east_m);

struct ReflectanceOrthoSummary {
  int rows = 0;
  int cols = 0;
  std::int64_t valid_pixels = 0;
  NorthUpGrid grid;
};

ReflectanceOrthoSummary writeReflectanceOrtho(const std::filesystem::path& hdr_path,
                                              const SwathFootprint& footprint,
                                              const RenderContext& context,
                                              const std::vector<double>& wavelengths_nm,
                                              std::ostream& log);

}  // namespace hsmap
