#pragma once
// The stages of `hsmap run` (run_command.h), one function each: run the
// stage's pipeline on the survey, write its products into the run folder
// (options.out) and tell the user what happened on `out` (progress, the
// stage's report, what was written). Errors propagate as exceptions; the
// runner turns them into its exit status.
//
//   frontend   RGB frames -> RUN/frontend/ (docs/FRONTEND.md)
//   georef     front-end + INS (sequential) or the INS alone (planar) ->
//              RUN/trajectory/, calibration.yaml, map/sparse.ply (docs/GEOREF.md)
//   surface    the adjusted map -> RUN/map/mesh.ply (docs/SURFACE.md)
//   products   RUN/trajectory/uhi_lines.csv + RUN/map/mesh.ply + the cube ->
//              RUN/hyperspectral/ (docs/PRODUCTS.md). It reads its inputs from
//              the run folder, so `--from products` reruns it alone.
//   joint      the joint problem (pipelines/joint) in rounds, each re-casting
//              the products: joint_stage.h (docs/JOINT.md).
#include <functional>
#include <iosfwd>
#include <optional>

#include "core/geometry/utm_projection.h"
#include "core/io/ply_io.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "core/survey/survey.h"
#include "pipelines/hyperspectral/hyperspectral_ortho.h"
#include "pipelines/frontend/frontend_runner.h"
#include "pipelines/georef/georef_result.h"
#include "tools/hsmap/run_command.h"

namespace hsmap {

FrontendResult runFrontendStage(const Survey& survey, const RunOptions& options, std::ostream& out);

GeorefResult runGeorefStage(const Survey& survey, const std::optional<FrontendResult>& frontend,
                            const RunOptions& options, std::ostream& out);

void runSurfaceStage(const Survey& survey, const GeorefResult& georef, const RunOptions& options,
                     std::ostream& out);

void runProductsStage(const Survey& survey, const RunOptions& options, std::ostream& out);

// Shared by the products and joint stages.
// One cast of every scan line onto the mesh: the hyperspectral products in
// RUN/hyperspectral (the GeoTIFF only when `geotiff`; the point cloud
// points.ply when `points` and options.points). `on_grid` as
// HyperspectralOptions::on_grid.
HyperspectralReport castProducts(const Survey& survey, const std::vector<LinePose>& line_poses,
                                 const MeshRayCaster& mesh, const UtmProjection& projection,
                                 const RunOptions& options, bool geotiff, std::ostream& out,
                                 bool points = true, std::function<void(const OrthoGrid&)> on_grid = {});
// RUN/hyperspectral/points.ply from these line poses (nothing when
// options.points is false).
void writePointCloudProducts(const Survey& survey, const std::vector<LinePose>& line_poses,
                             const MeshRayCaster& mesh, const RunOptions& options, std::ostream& out);
// RUN/map/rgb_ortho.png (+ .tif): the textured mesh on the ortho grid, cast
// through `mesh` (built from `ply`).
void writeRgbOrthoProducts(const PlyMesh& ply, const MeshRayCaster& mesh, const OrthoGrid& grid,
                           const UtmProjection& projection, const RunOptions& options, std::ostream& out);

}  // namespace hsmap
