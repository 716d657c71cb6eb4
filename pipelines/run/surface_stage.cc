#include "pipelines/run/surface_stage.h"

#include <ostream>

#include "core/io/ply_io.h"
#include "pipelines/georef/georef_outputs.h"
#include "pipelines/surface/surface_meshing.h"

namespace hsmap {

void runSurfaceStage(const StageContext& context, const SurfaceStageOptions& options) {
  options.validate();
  const auto georef_folder = context.run / stage_folders::georef;
  const GeorefResult georef = readGeorefOutputs(georef_folder);
  const SurfaceMode mode = context.variant == Variant::planar ? SurfaceMode::flat : options.mode;
  const PlyMesh mesh = meshSurface(context.survey, georef, mode, options.seabed_depth_m, context.out);
  const auto path = context.run / stage_folders::surface / stage_folders::mesh_ply;
  std::filesystem::create_directories(path.parent_path());
  writePly(path, mesh);  // atomic: mesh.ply.partial, then renamed
  context.out << "surface (" << toString(mode) << "): " << mesh.vertices.size() << " vertices, "
              << mesh.triangles.size() << " triangles; wrote " << path.string() << "\n";
}

}  // namespace hsmap
