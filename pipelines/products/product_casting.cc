#include "pipelines/products/product_casting.h"

#include <ostream>

#include "core/geometry/pushbroom_camera.h"
#include "pipelines/products/hyperspectral_point_cloud.h"
#include "pipelines/products/rgb_ortho.h"

namespace hsmap {

namespace fs = std::filesystem;

HyperspectralReport castHyperspectralOrtho(const Survey& survey, const PushbroomParameters& uhi_camera,
                                           const std::vector<LinePose>& line_poses,
                                           const MeshRayCaster& mesh, const UtmProjection& projection,
                                           const fs::path& folder, double pixel_m, bool geotiff,
                                           std::ostream& out, std::function<void(const OrthoGrid&)> on_grid) {
  if (!survey.cube) throw std::invalid_argument("castHyperspectralOrtho: the survey's UHI cube is not open");
  HyperspectralOptions products;
  products.pixel_m = pixel_m;
  products.write_geotiff = geotiff;
  products.on_grid = std::move(on_grid);
  const HyperspectralReport report =
      writeHyperspectralOrtho(*survey.cube, survey.wavelengths_nm, PushbroomCamera(uhi_camera),
                              line_poses, mesh, projection, folder, products, out);
  out << report.summary();
  return report;
}

void writePointCloud(const Survey& survey, const PushbroomParameters& uhi_camera,
                     const std::vector<LinePose>& line_poses, const MeshRayCaster& mesh,
                     const fs::path& ply, double cell_m, std::ostream& out) {
  if (!survey.cube) throw std::invalid_argument("writePointCloud: the survey's UHI cube is not open");
  HyperspectralPointCloudOptions points;
  points.cell_m = cell_m;
  const HyperspectralPointCloudReport report =
      writeHyperspectralPointCloud(*survey.cube, survey.wavelengths_nm, PushbroomCamera(uhi_camera),
                                   line_poses, mesh, survey.origin, ply, points, out);
  out << report.summary() << "wrote " << report.ply.string() << "\n";
}

void writeRgbOrthoImage(const PlyMesh& ply, const MeshRayCaster& mesh, const OrthoGrid& grid,
                        const UtmProjection& projection, const fs::path& folder, bool geotiff, std::ostream& out) {
  // The RGB ortho-image of the textured mesh on the same grid, to compare
  // side by side (and, with its 3D points, to match against).
  if (ply.colors.size() != ply.vertices.size()) {
    out << "warning: products: the mesh has no vertex colours: no RGB ortho-image\n";
    return;
  }
  RgbOrthoOptions rgb;
  rgb.write_geotiff = geotiff;
  const RgbOrthoReport rgb_report = writeRgbOrtho(ply, mesh, grid, projection, folder, rgb);
  out << rgb_report.summary() << "\n";
  out << "wrote";
  for (const fs::path& path : {rgb_report.png, rgb_report.tif}) {
    if (!path.empty()) out << " " << path.string();
  }
  out << "\n";
}

}  // namespace hsmap
