#pragma once
// The `stacked` variant's products (DESIGN.md, "Estimation variants"): the
// scan lines written side by side, as a push-broom camera delivers them, with
// no pose, no surface and no map position. It is the picture a user gets
// without hsmap, written in the same files as the other variants' products
// so that they compare side by side:
//
//   RUN/hyperspectral/ortho.hdr/.raw      ENVI float32 BIL, row = scan line (cube order),
//                                         column = sample, every band with its wavelength;
//                                         no `map info`. A spectrum with a NaN or infinite
//                                         band, or the cube's `data ignore value`, is NaN
//                                         (counted), never copied as a number.
//   RUN/hyperspectral/ortho_rgb.png       quick-look (ortho_quicklook.h), same bands and stretch
//   RUN/hyperspectral/ancillary.hdr/.raw  scan line and sample of every pixel; range and
//                                         incidence NaN (nothing was cast)
//
// No GeoTIFF: a raster without a map position would only mislead a GIS.
// The cube is streamed line by line; memory is a few lines.

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/io/envi_reader.h"

namespace hsmap {

struct StackedReport {
  std::int64_t lines = 0, samples = 0;
  int bands = 0;
  std::int64_t skipped_non_finite = 0;    // pixels whose spectrum had a NaN/inf band
  std::int64_t skipped_ignore_value = 0;  // pixels whose spectrum had the data ignore value
  double seconds = 0.0;
  std::filesystem::path ortho_hdr, quicklook_png, ancillary_hdr;

  std::string summary() const;
};

// Throws std::invalid_argument when the wavelengths do not match the cube's
// bands, InputError for an unreadable `data ignore value`, what EnviReader
// and EnviWriter throw.
StackedReport writeStackedProducts(const EnviReader& cube, const std::vector<double>& wavelengths_nm,
                                   const std::filesystem::path& out_folder, std::ostream& log,
                                   int quicklook_max_side = 8192);

}  // namespace hsmap
