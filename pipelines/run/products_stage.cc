#include "pipelines/run/products_stage.h"

#include <chrono>
#include <future>
#include <ostream>
#include <sstream>
#include <string>

#include "core/geometry/utm_projection.h"
#include "core/io/results_folder.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "core/survey/run_calibration.h"
#include "core/util/stage_timer.h"
#include "pipelines/products/product_casting.h"
#include "pipelines/products/stacked_products.h"
#include "pipelines/radiometry/radiometry_files.h"
#include "pipelines/radiometry/reflectance_ortho.h"

namespace hsmap {

namespace fs = std::filesystem;

void runProductsStage(const StageContext& context, const ProductsStageOptions& options) {
  options.validate();
  std::ostream& out = context.out;
  const Survey& survey = context.survey;
  if (!survey.cube) throw std::invalid_argument("the survey's UHI cube is not open");
  const fs::path folder = context.run / "hyperspectral";
  if (context.variant == Variant::stacked) {
    const StackedReport report = writeStackedProducts(*survey.cube, survey.wavelengths_nm, folder, out);
    out << report.summary() << "\n";
    out << "wrote " << report.ortho_hdr.string() << ", " << report.quicklook_png.string() << ", "
        << report.ancillary_hdr.string() << " (no GeoTIFF and no RGB ortho-image: no map position)\n";
    return;
  }
  const fs::path lines_csv = context.run / results_paths::trajectory_uhi_lines;
  const fs::path mesh_ply = context.run / results_paths::mesh_ply;
  out << "products: scan line poses from " << lines_csv.string() << ", surface from " << mesh_ply.string()
      << "\n";
  const std::vector<LinePose> line_poses = readLinePoseTable(lines_csv);
  const auto mesh_start = std::chrono::steady_clock::now();
  const PlyMesh ply = readSurfaceMesh(mesh_ply);
  const double read_mesh_s = secondsSince(mesh_start);
  const MeshRayCaster mesh(ply.vertices, ply.triangles);
  out << "products: mesh read and its BVH built in " << secondsSince(mesh_start) << " s ("
      << ply.triangles.size() << " triangles; read " << read_mesh_s << " s)\n";
  const UtmProjection projection(survey.origin);
  // The contract file says which UHI camera the run settled on: the joint
  // stage's estimate when it self-calibrated the intrinsics, else survey.yaml's.
  PushbroomParameters uhi_camera = survey.config.uhi.camera;
  const fs::path calibration_yaml = context.run / results_paths::calibration_yaml;
  if (fs::exists(calibration_yaml)) {
    const RunCalibration calibration = readRunCalibration(calibration_yaml);
    if (calibration.uhi_camera) {
      uhi_camera = calibration.uhi_camera->appliedTo(uhi_camera);
      out << "products: the UHI camera of " << calibration_yaml.string() << " (f " << uhi_camera.f << ", cx "
          << uhi_camera.cx << ", distortion [" << uhi_camera.distortion[0] << ", " << uhi_camera.distortion[1]
          << "])\n";
    }
  }

  // The RGB ortho-image (on the cast's grid) is rendered alongside the
  // tiles, which wait on the disk; its log follows the cast's.
  std::future<std::string> rgb_ortho;
  auto startRgbOrtho = [&](const OrthoGrid& grid) {
    rgb_ortho = std::async(std::launch::async, [&, grid] {
      std::ostringstream log;
      writeRgbOrthoImage(ply, mesh, grid, projection, context.run / "map", options.geotiff, log);
      return log.str();
    });
  };
  const HyperspectralReport report = castHyperspectralOrtho(survey, uhi_camera, line_poses, mesh, projection, folder,
                                                            options.ortho_pixel_m, options.geotiff, out,
                                                            startRgbOrtho);
  if (options.points) writePointCloud(survey, uhi_camera, line_poses, mesh, folder / "points.ply", options.point_cell_m, out);
  out << "wrote " << report.ortho_hdr.string();
  for (const fs::path& path : {report.ortho_tif, report.quicklook_png, report.ancillary_hdr}) {
    if (!path.empty()) out << ", " << path.string();
  }
  if (options.points) out << ", " << (folder / "points.ply").string();
  out << "\n";
  out << rgb_ortho.get();  // on_grid is called before the first tile of every cast

  // Reflectance: the radiance ortho corrected with the radiometry stage's estimate.
  const fs::path water_yaml = context.run / radiometry_files::folder / radiometry_files::water;
  if (!survey.config.lights) {
    out << "products: no reflectance: survey.yaml has no `lights` block (radiance products only)\n";
  } else if (!fs::exists(water_yaml)) {
    out << "products: no reflectance: the radiometry stage left no estimate (" << water_yaml.string() << ")\n";
  } else {
    SE3d T_C_U(survey.config.uhi.T_C_U.rotation, survey.config.uhi.T_C_U.translation_m);
    if (fs::exists(calibration_yaml)) {
      const RunCalibration calibration = readRunCalibration(calibration_yaml);
      T_C_U = SE3d(calibration.T_C_U.rotation, calibration.T_C_U.translation_m);
    }
    ReflectanceOptions reflectance;
    reflectance.write_geotiff = options.geotiff;
    const ReflectanceReport reflectance_report =
        writeReflectanceOrtho(folder, PushbroomCamera(uhi_camera), line_poses, mesh, *survey.config.lights, T_C_U,
                              survey.lamp_response_dn, readWaterEstimate(water_yaml), reflectance);
    out << reflectance_report.summary();
    out << "wrote " << reflectance_report.hdr.string();
    if (!reflectance_report.tif.empty()) out << ", " << reflectance_report.tif.string();
    out << "\n";
  }
}

}  // namespace hsmap
