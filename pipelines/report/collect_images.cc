#include "pipelines/report/collect_images.h"

#include "core/io/envi_header.h"
#include "core/io/ply_io.h"
#include "core/io/results_folder.h"
#include "pipelines/report/mesh_top_view.h"
#include "pipelines/report/page_image.h"
#include "pipelines/report/spectral_grid.h"

namespace hsmap {

namespace fs = std::filesystem;

void collectImages(const fs::path& run, ReportData& data) {
  std::error_code error;
  const fs::path quick_look = run / results_paths::ortho_rgb_png;
  const fs::path rgb_ortho = run / "map" / "rgb_ortho.png";
  const fs::path ortho_hdr = run / results_paths::ortho_hdr;
  if (fs::is_regular_file(quick_look, error)) {
    data.hyperspectral_ortho = readPageImage(quick_look, kOrthoMaxSide);
  } else {
    data.notes.push_back("no hyperspectral ortho-image: " + quick_look.string() +
                         " is missing (the products stage has not run)");
  }
  if (fs::is_regular_file(rgb_ortho, error)) {
    data.rgb_ortho = readPageImage(rgb_ortho, kOrthoMaxSide);
  } else {
    data.notes.push_back("no RGB ortho-image: " + rgb_ortho.string() + " is missing (the " + data.variant +
                         " variant has no textured mesh, or the products stage has not run)");
  }
  if (fs::is_regular_file(ortho_hdr, error)) {
    const EnviHeader header = readEnviHeader(ortho_hdr);
    if (header.map_info) data.ortho_pixel_m = header.map_info->pixel_size_x;
    data.spectra = readSpectralGrid(ortho_hdr);
  }

  const fs::path mesh_ply = run / results_paths::mesh_ply;
  if (!fs::is_regular_file(mesh_ply, error)) {
    data.notes.push_back("no mesh top view: " + mesh_ply.string() + " is missing");
    return;
  }
  const PlyMesh mesh = readPly(mesh_ply);
  if (mesh.triangles.empty()) {
    data.notes.push_back("no mesh top view: " + mesh_ply.string() + " has no triangles");
    return;
  }
  const MeshTopView view = rasteriseMeshTopView(mesh, kTopViewMaxSide);
  ReportTopView top;
  top.image = encodePageImage(view.image, kTopViewMaxSide, mesh_ply.string());
  top.north_max = view.north_max;
  top.east_min = view.east_min;
  top.pixel_m = view.pixel_m;
  data.mesh_top_view = top;
  for (const ReportPosition& frame : data.frames) data.seabed_down.push_back(view.downAt(frame.north, frame.east));
}

}  // namespace hsmap
