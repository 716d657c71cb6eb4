#pragma once
// The hyperspectral ortho-image (RUN/hyperspectral/ortho.hdr) reduced to the
// spectral grid the page reads spectra from (ReportSpectralGrid): the mean
// spectrum of each block of block_px x block_px pixels, over the pixels that
// have data, with block_px the smallest that keeps the grid within
// `max_blocks` blocks and `max_values` numbers (blocks x bands: about 2 bytes
// each on the page, 2.7 after base64). Read one scan line at a time, so
// memory stays at one line and one row of blocks whatever the ortho's size.

#include <filesystem>

#include "pipelines/report/report_data.h"

namespace hsmap {

inline constexpr long long kSpectralGridMaxBlocks = 96 * 96;
inline constexpr long long kSpectralGridMaxValues = 1'000'000;

// InputError for a header or data file that cannot be read.
ReportSpectralGrid readSpectralGrid(const std::filesystem::path& ortho_hdr,
                                    long long max_blocks = kSpectralGridMaxBlocks,
                                    long long max_values = kSpectralGridMaxValues);

}  // namespace hsmap
