#pragma once
// The report's images: the hyperspectral quick-look
// (hyperspectral/ortho_rgb.png) and the RGB ortho-image (map/rgb_ortho.png),
// which lie on the same grid, downsampled alike so that the page can swipe
// and blink between them; the spectral grid of hyperspectral/ortho.hdr; and
// the mesh (map/mesh.ply) seen from above, whose heights also give the
// seabed under each frame (data.seabed_down, for the altitude profile).

#include <filesystem>

#include "pipelines/report/report_data.h"

namespace hsmap {

// Longer sides on the page: the ortho-images are zoomable, so they keep more.
inline constexpr int kOrthoMaxSide = 1600;
inline constexpr int kTopViewMaxSide = 1000;

// Needs data.frames (collectTrajectory) for seabed_down. InputError for a
// product that cannot be read.
void collectImages(const std::filesystem::path& run, ReportData& data);

}  // namespace hsmap
