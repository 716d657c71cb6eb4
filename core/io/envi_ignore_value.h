#pragma once
// The `data ignore value` of an ENVI header: the value that marks a pixel
// without data (ENVI's own key, kept by EnviHeader among other_fields as
// written). Keys match as ENVI matches them: case and runs of blanks do not
// matter ("Data  Ignore Value"); braces around the value are allowed.
//
// Returns the value as a float (samples are compared as floats), nullopt when
// the header has no such key or the value is NaN (NaN marks nothing beyond
// the NaN check every reader of hsmap's rasters already does). Throws
// InputError naming the header and the key for anything else that is not a
// finite number, e.g.
//   "ortho.hdr:key data ignore value: expected a finite number or NaN, found 'none'".
#include <filesystem>
#include <optional>

#include "core/io/envi_header.h"

namespace hsmap {

std::optional<float> enviDataIgnoreValue(const EnviHeader& header, const std::filesystem::path& hdr_path);

// Declares NaN as the raster's `data ignore value` (replacing any value the
// header had): what hsmap's float products write where nothing was seen.
// GDAL's ENVI driver then reports NoData = NaN, as the GeoTIFF export
// declares it, so a GIS shows those pixels as empty from either file.
void setDataIgnoreValueNaN(EnviHeader& header);

}  // namespace hsmap
