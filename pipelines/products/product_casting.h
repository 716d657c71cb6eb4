#pragma once
// Casting the survey's scan lines onto a mesh and writing what comes of it:
// the shared work of every stage that needs ortho-images (products writes the
// run's; refine and joint cast into their own scratch folders to match
// against). Each function writes into the folder it is given.
//
//   castHyperspectralOrtho   FOLDER/ortho.hdr+raw (+ .tif), ortho_rgb.png,
//                            ancillary.hdr+raw (hyperspectral_ortho.h)
//   writePointCloud          FOLDER/points.ply (hyperspectral_point_cloud.h)
//   writeRgbOrthoImage       FOLDER/rgb_ortho.png (+ .tif) (rgb_ortho.h)

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <vector>

#include "core/geometry/utm_projection.h"
#include "core/io/ply_io.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "core/survey/survey.h"
#include "pipelines/products/hyperspectral_ortho.h"

namespace hsmap {

// One cast of every scan line of `line_poses` onto `mesh` through
// `uhi_camera` (survey.yaml's, or the run's estimate in calibration.yaml's
// uhi_camera): the ortho-image
// at `pixel_m`, its quick-look, ancillary layers and (when `geotiff`) its COG
// GeoTIFF in `folder`. `on_grid` as HyperspectralOptions::on_grid. The
// report's summary goes to `out`.
HyperspectralReport castHyperspectralOrtho(const Survey& survey, const PushbroomParameters& uhi_camera,
                                           const std::vector<LinePose>& line_poses,
                                           const MeshRayCaster& mesh, const UtmProjection& projection,
                                           const std::filesystem::path& folder, double pixel_m, bool geotiff,
                                           std::ostream& out,
                                           std::function<void(const OrthoGrid&)> on_grid = {});

// `ply` (points.ply) from these line poses through `uhi_camera`: the hits
// binned into cubes of `cell_m` metres.
void writePointCloud(const Survey& survey, const PushbroomParameters& uhi_camera,
                     const std::vector<LinePose>& line_poses, const MeshRayCaster& mesh,
                     const std::filesystem::path& ply, double cell_m, std::ostream& out);

// The textured mesh `ply` (cast through `mesh`, built from it) on `grid`:
// FOLDER/rgb_ortho.png and, when `geotiff`, rgb_ortho.tif. A mesh without
// vertex colours gives a warning on `out` and no image.
void writeRgbOrthoImage(const PlyMesh& ply, const MeshRayCaster& mesh, const OrthoGrid& grid,
                        const UtmProjection& projection, const std::filesystem::path& folder, bool geotiff,
                        std::ostream& out);

}  // namespace hsmap
