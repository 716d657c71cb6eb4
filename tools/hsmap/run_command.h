#pragma once
// `hsmap run SURVEY --out RUN [--variant V] [--until STAGE] [--from STAGE]`:
// the stages of a run, in order, each writing its products into the run
// folder (the data contract's results folder; docs/SURVEY_FORMAT.md):
//
//   variant      stages
//   sequential   frontend (docs/FRONTEND.md), georef (docs/GEOREF.md),
//                surface (docs/SURFACE.md; --surface dense, the default, meshes
//                the keyframes' fused stereo depth maps; --surface sparse the
//                adjusted landmarks alone, the reference paper's way)
//   planar       georef (the INS alone: no vision), surface (a flat seabed at
//                --seabed-depth or at a depth estimated from RGB frame pairs
//                scaled by the INS: pipelines/surface/flat_seabed.h)
//   both         products (docs/PRODUCTS.md): every scan line cast onto the
//                surface, the hyperspectral ortho-image, its quick-look,
//                GeoTIFF and ancillary layers, the RGB ortho-image of the mesh;
//                for sequential, --extrinsic-rounds refinements of T_C_U from
//                the two ortho-images, each followed by a new cast
//   stacked      products only: the scan lines side by side (no poses, no
//                map position), the picture without hsmap
//
// --until names the last stage to run; --from the first (the earlier
// stages' files are read back from RUN, e.g. to rerun geo-referencing on a
// front-end already computed). run.yaml is written last, when every stage
// asked for has succeeded: a folder without it holds no finished run. With
// --force, an earlier run's run.yaml, metrics.json and the products of the
// stages about to run are removed first, so a run that fails never leaves
// an older product looking like its own.
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace hsmap {

struct RunOptions {
  std::filesystem::path survey;
  std::filesystem::path out;
  std::string variant = "sequential";
  std::string until;  // empty: the variant's last stage
  std::string from;   // empty: the variant's first stage
  bool force = false;
  std::string surface = "dense";  // dense or sparse
  double ortho_pixel_m = 0.005;    // products: ortho-image pixel size
  bool geotiff = true;             // products: also write hyperspectral/ortho.tif
  // products: hyperspectral/points.ply, the hits binned into cubes of
  // point_cell_m metres (mean position and spectrum a cube;
  // pipelines/hyperspectral/hyperspectral_point_cloud.h).
  bool points = true;
  double point_cell_m = 0.02;
  // sequential: rounds of the extrinsic refinement from the RGB and
  // hyperspectral ortho-images (0: keep survey.yaml's guess).
  int extrinsic_rounds = 2;
  // joint: rounds of tie points, joint solve and re-cast (fewer when T_C_U
  // and d stop moving).
  int joint_rounds = 3;
  // joint: where rounds after the first find their tie points: "strip" (the
  // push-broom strip against its prediction, strip_tie_points.h) or "ortho"
  // (the two ortho-images, as the first round always does).
  std::string joint_tie_points = "strip";
  // planar: the flat seabed's z in W (m, down); estimated when absent.
  std::optional<double> seabed_depth_m;
};

CLI::App* addRunCommand(CLI::App& app, RunOptions& options);
// Exit status: 0 on success, 1 for a usage error or a stage that fails
// (reported on `err`); InputError (bad survey) propagates to main (status 2).
int runRunCommand(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace hsmap
