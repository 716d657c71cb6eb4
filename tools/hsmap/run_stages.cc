#include "tools/hsmap/run_stages.h"

#include <chrono>
#include <cstdio>
#include <functional>
#include <future>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>

#include "core/io/geotiff_export.h"
#include "core/io/ply_io.h"
#include "core/io/results_folder.h"
#include "core/survey/pose_tables.h"
#include "core/survey/run_calibration.h"
#include "core/geometry/utm_projection.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/util/progress.h"
#include "pipelines/frontend/frontend_outputs.h"
#include "pipelines/frontend/frontend_runner.h"
#include "pipelines/georef/georef_outputs.h"
#include "pipelines/georef/planar_georef.h"
#include "pipelines/georef/sequential_georef.h"
#include "pipelines/hyperspectral/hyperspectral_ortho.h"
#include "pipelines/hyperspectral/extrinsic_refinement.h"
#include "pipelines/hyperspectral/hyperspectral_point_cloud.h"
#include "pipelines/hyperspectral/rgb_ortho.h"
#include "pipelines/hyperspectral/stacked_products.h"
#include "pipelines/surface/dense_surface.h"
#include "pipelines/surface/flat_seabed.h"
#include "pipelines/surface/sparse_map_points.h"
#include "pipelines/surface/surface_reconstruction.h"
#include "pipelines/surface/vertex_colours.h"

namespace hsmap {

namespace fs = std::filesystem;

namespace {

// The surface from the adjusted sparse map alone (--surface sparse, the
// reference paper's way; docs/SURFACE.md): its landmarks, the keyframes that
// saw them, Delaunay and the visibility cut. Not cleaned: the landmarks'
// spacing is irregular, so the dense mesh's long-edge and spike tests would
// cut away real triangles (on rugged the completeness fell from 0.94 to 0.84).
PlyMesh sparseSurface(const Survey& survey, const GeorefResult& georef, std::ostream& out) {
  const VisibilityPoints points = visibilityFromSparseMap(georef.map_W);
  out << "surface: " << points.p_W.size() << " landmarks seen from " << points.c_W.size()
      << " keyframes...\n";
  const SurfaceReconstruction surface = reconstructSurface(points);
  const SurfaceMesh& cleaned = surface.mesh;
  PlyMesh mesh;
  mesh.vertices = cleaned.vertices;
  mesh.triangles = cleaned.triangles;
  const VertexColours colours = colourVerticesFromKeyframes(
      cleaned, points, georef.map_W, survey.rgb, PinholeRadtanCamera(survey.config.rgb.camera));
  mesh.colors = colours.rgb;
  const SurfaceCutReport& r = surface.report;
  char line[320];
  std::snprintf(line, sizeof(line),
                "surface (sparse landmarks): %lld points, %lld rays, %lld of %lld cells inside, "
                "%zu triangles; Delaunay %.1f s, rays %.1f s, cut %.1f s\n",
                static_cast<long long>(r.points), static_cast<long long>(r.rays),
                static_cast<long long>(r.inside_cells), static_cast<long long>(r.cells),
                mesh.triangles.size(), r.seconds_triangulation,
                r.seconds_rays, r.seconds_cut);
  out << line << "  vertex colours from " << colours.images_decoded << " keyframe images";
  if (colours.uncoloured > 0) out << "; " << colours.uncoloured << " vertices seen by none (grey)";
  out << "\n";
  return mesh;
}

// The dense surface (docs/SURFACE.md): stereo depth maps of the keyframes,
// fused, meshed tile by tile and stitched.
PlyMesh denseSurface(const Survey& survey, const GeorefResult& georef, std::ostream& out) {
  std::optional<Progress> depth_maps, tiles;
  const DenseSurface surface = reconstructDenseSurface(
      georef.map_W, survey.rgb, PinholeRadtanCamera(survey.config.rgb.camera),
      DenseSurfaceOptions{}, [&](const std::string& what, int done, int total) {
        std::optional<Progress>& bar = what == "tiles" ? tiles : depth_maps;
        if (!bar) bar.emplace("surface: " + what, total, what == "tiles" ? "tiles" : "keyframes", out);
        bar->advance(done - bar->done());
      });
  if (depth_maps) depth_maps->finish();
  if (tiles) tiles->finish();
  out << surface.report.summary() << "\n";
  for (const auto& warning : surface.report.warnings) out << "warning: surface: " << warning << "\n";
  PlyMesh mesh;
  mesh.vertices = surface.vertices;
  mesh.triangles = surface.triangles;
  mesh.colors = surface.colours;
  return mesh;
}

// The planar variant's surface: a horizontal plane at the seabed depth,
// given (--seabed-depth) or estimated from RGB frame pairs scaled by the
// INS track (flat_seabed.h), under every frame and scan line with a margin
// that covers what a camera at that altitude sees.
PlyMesh flatSurface(const Survey& survey, const GeorefResult& georef, const RunOptions& options,
                    std::ostream& out) {
  double depth = 0.0, altitude = 2.0;
  if (options.seabed_depth_m) {
    depth = *options.seabed_depth_m;
    out << "surface (flat): seabed at z = " << depth << " m, as given by --seabed-depth\n";
  } else {
    out << "surface (flat): estimating the seabed depth from RGB frame pairs and the INS track...\n";
    const SeabedDepthEstimate estimate = estimateSeabedDepth(survey, georef.frames);
    depth = estimate.depth_m;
    altitude = estimate.altitude_m;
    out << "surface (flat): " << estimate.summary() << "\n";
  }
  std::vector<Eigen::Vector3d> positions_W;
  for (const GeorefFramePose& frame : georef.frames) positions_W.push_back(frame.T_W_C.t);
  for (const GeorefLinePose& line : georef.lines) positions_W.push_back(line.T_W_U.t);
  if (!options.seabed_depth_m) {
    double sum = 0.0;
    for (const auto& p : positions_W) sum += depth - p.z();
    altitude = std::max(altitude, sum / double(positions_W.size()));
  }
  return flatSeabedMesh(depth, positions_W, 2.0 * std::abs(altitude) + 2.0);
}

}  // namespace

FrontendResult runFrontendStage(const Survey& survey, const RunOptions& options, std::ostream& out) {
  FrontendOptions frontend_options;
  Progress progress("frontend", survey.rgb.frameCount(), "frames", out);
  int reported = 0;
  FrontendResult result = runFrontend(survey, frontend_options, [&](int done, int, double) {
    progress.advance(done - reported);
    reported = done;
  });
  progress.finish();
  writeFrontendOutputs(options.out, result);
  out << result.summary() << "\n";
  for (const auto& warning : result.warnings) out << "warning: " << warning << "\n";
  out << "wrote " << (options.out / frontend_files::folder).string() << "/\n";
  return result;
}

void runSurfaceStage(const Survey& survey, const GeorefResult& georef, const RunOptions& options,
                     std::ostream& out) {
  const PlyMesh mesh = options.variant == "planar"   ? flatSurface(survey, georef, options, out)
                       : options.surface == "sparse" ? sparseSurface(survey, georef, out)
                                                     : denseSurface(survey, georef, out);
  const fs::path path = options.out / results_paths::mesh_ply;
  fs::create_directories(path.parent_path());
  writePly(path, mesh);
  out << "surface (" << (options.variant == "planar" ? "flat" : options.surface) << "): " << mesh.vertices.size() << " vertices, "
      << mesh.triangles.size() << " triangles; wrote " << results_paths::mesh_ply << " in "
      << options.out.string() << "\n";
}

void writePointCloudProducts(const Survey& survey, const std::vector<LinePose>& line_poses,
                             const MeshRayCaster& mesh, const RunOptions& options, std::ostream& out) {
  if (!options.points) return;
  HyperspectralPointCloudOptions points;
  points.cell_m = options.point_cell_m;
  const HyperspectralPointCloudReport report = writeHyperspectralPointCloud(
      *survey.cube, survey.wavelengths_nm, PushbroomCamera(survey.config.uhi.camera), line_poses, mesh,
      survey.origin, options.out / "hyperspectral/points.ply", points, out);
  out << report.summary() << "wrote " << report.ply.string() << "\n";
}

HyperspectralReport castProducts(const Survey& survey, const std::vector<LinePose>& line_poses,
                                 const MeshRayCaster& mesh, const UtmProjection& projection,
                                 const RunOptions& options, bool geotiff, std::ostream& out, bool points,
                                 std::function<void(const OrthoGrid&)> on_grid) {
  HyperspectralOptions products;
  products.pixel_m = options.ortho_pixel_m;
  products.write_geotiff = geotiff;
  products.on_grid = std::move(on_grid);
  const HyperspectralReport report = writeHyperspectralOrtho(
      *survey.cube, survey.wavelengths_nm, PushbroomCamera(survey.config.uhi.camera), line_poses, mesh,
      projection, options.out / "hyperspectral", products, out);
  out << report.summary();
  if (points) writePointCloudProducts(survey, line_poses, mesh, options, out);
  return report;
}

GeorefResult runGeorefStage(const Survey& survey, const std::optional<FrontendResult>& frontend,
                            const RunOptions& options, std::ostream& out) {
  GeorefOptions georef_options;
  GeorefResult result;
  if (options.variant == "planar") {
    result = runPlanarGeoref(survey, georef_options);
  } else {
    std::optional<Progress> frames;
    result = runSequentialGeoref(survey, *frontend, georef_options,
                                 [&](const std::string& step, int done, int total) {
                                   if (step != "frames") {
                                     if (done == 0) out << "georef: " << step << "...\n";
                                     return;
                                   }
                                   if (!frames) frames.emplace("georef: posing frames", total, "frames", out);
                                   frames->advance(done - frames->done());
                                 });
    if (frames) frames->finish();
  }
  // The joint variant starts from the sequential result and says so in its
  // files until the joint stage replaces them.
  if (options.variant == "joint") result.variant = "joint";
  writeGeorefOutputs(options.out, result);
  out << result.summary() << "\n";
  for (const auto& warning : result.warnings) out << "warning: " << warning << "\n";
  out << "wrote";
  for (const auto& path : georefProductPaths(result)) out << " " << path.string();
  out << " in " << options.out.string() << "\n";
  return result;
}


namespace {

SE3d toSe3(const RigidTransformConfig& T) { return SE3d(T.rotation, T.translation_m); }

// The reference paper's refinement of T_C_U (pipelines/hyperspectral/
// extrinsic_refinement.h), `rounds` times: match the RGB and hyperspectral
// ortho-images, refine, rewrite the line poses and calibration.yaml, cast
// again; `report` becomes the last cast's.
void refineExtrinsic(const Survey& survey, std::vector<LinePose> line_poses, const MeshRayCaster& mesh,
                     const UtmProjection& projection, const RunOptions& options, HyperspectralReport& report,
                     std::ostream& out) {
  const fs::path calibration_yaml = options.out / results_paths::calibration_yaml;
  RunCalibration calibration = readRunCalibration(calibration_yaml);
  const ExtrinsicPrior prior{toSe3(survey.config.uhi.T_C_U), survey.config.uhi.sigma_rotation_deg,
                             survey.config.uhi.sigma_translation_m, survey.config.uhi.time_offset_sigma_s};
  for (int round = 1; round <= options.extrinsic_rounds; ++round) {
    const SE3d T_C_U_lines = toSe3(calibration.T_C_U);
    out << "products: extrinsic refinement, round " << round << " of " << options.extrinsic_rounds << "\n";
    const ExtrinsicRefinementResult result = refineExtrinsicInRun(
        options.out, T_C_U_lines, survey.config.uhi.camera, prior, projection, ExtrinsicRefinementOptions{}, out);
    if (!result.refined) {
      out << "products: T_C_U kept at " << (round == 1 ? "the survey's guess" : "the last round's result")
          << "\n";
      for (const auto& warning : result.warnings) {
        calibration.warnings.push_back("extrinsic refinement, round " + std::to_string(round) + ": " + warning);
      }
      writeRunCalibration(calibration_yaml, calibration);
      // The last cast skipped the point cloud (a round was to follow).
      writePointCloudProducts(survey, line_poses, mesh, options, out);
      break;
    }
    line_poses = updatedLinePoses(line_poses, T_C_U_lines, result.T_C_U);
    std::vector<TimedPose> lines_timed;
    for (const LinePose& line : line_poses) lines_timed.push_back({line.t, line.T});
    writeLinePoseTable(options.out / results_paths::trajectory_uhi_lines, line_poses);
    writeTumTrajectory(options.out / "trajectory/uhi_lines.tum", lines_timed);
    calibration.T_C_U.rotation = result.T_C_U.q;
    calibration.T_C_U.translation_m = result.T_C_U.t;
    calibration.sigma_rotation_deg = result.sigma_rotation_deg;
    calibration.sigma_translation_m = result.sigma_translation_m;
    calibration.warnings = {"T_C_U refined from the RGB and hyperspectral ortho-images (" +
                                std::to_string(result.inliers) + " tie points, round " +
                                std::to_string(round) + "); time_offset_s is the survey.yaml guess: the " +
                                calibration.variant + " variant does not estimate it, and T_C_U's 1-sigma " +
                                "includes what the guess's own 1-sigma can move it by"};
    writeRunCalibration(calibration_yaml, calibration);
    out << "products: wrote the refined T_C_U into " << calibration_yaml.string() << " and the scan line poses "
        << "into " << results_paths::trajectory_uhi_lines << "; casting again\n";
    report = castProducts(survey, line_poses, mesh, projection, options, false, out,
                          round == options.extrinsic_rounds);
  }
}

}  // namespace

void writeRgbOrthoProducts(const PlyMesh& ply, const MeshRayCaster& mesh, const OrthoGrid& grid,
                           const UtmProjection& projection, const RunOptions& options, std::ostream& out) {
  // The RGB ortho-image of the textured mesh on the same grid, to compare
  // side by side (and, with its 3D points, to match against).
  if (ply.colors.size() != ply.vertices.size()) {
    out << "warning: products: " << (options.out / results_paths::mesh_ply).string()
        << " has no vertex colours: no RGB ortho-image\n";
    return;
  }
  RgbOrthoOptions rgb;
  rgb.write_geotiff = options.geotiff;
  const RgbOrthoReport rgb_report = writeRgbOrtho(ply, mesh, grid, projection, options.out / "map", rgb);
  out << rgb_report.summary() << "\n";
  out << "wrote";
  for (const fs::path& path : {rgb_report.png, rgb_report.tif}) {
    if (!path.empty()) out << " " << path.string();
  }
  out << "\n";
}

void runProductsStage(const Survey& survey, const RunOptions& options, std::ostream& out) {
  if (!survey.cube) throw std::invalid_argument("the survey's UHI cube is not open");
  if (options.variant == "stacked") {
    const StackedReport report =
        writeStackedProducts(*survey.cube, survey.wavelengths_nm, options.out / "hyperspectral", out);
    out << report.summary() << "\n";
    out << "wrote " << report.ortho_hdr.string() << ", " << report.quicklook_png.string() << ", "
        << report.ancillary_hdr.string() << " (no GeoTIFF and no RGB ortho-image: no map position)\n";
    return;
  }
  const fs::path lines_csv = options.out / results_paths::trajectory_uhi_lines;
  const fs::path mesh_ply = options.out / results_paths::mesh_ply;
  out << "products: scan line poses from " << lines_csv.string() << ", surface from "
      << mesh_ply.string() << "\n";
  const std::vector<LinePose> line_poses = readLinePoseTable(lines_csv);
  const auto mesh_start = std::chrono::steady_clock::now();
  const PlyMesh ply = readSurfaceMesh(mesh_ply);
  const double read_mesh_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - mesh_start).count();
  const UtmProjection projection(survey.origin);
  const bool refine = options.variant == "sequential" && options.extrinsic_rounds > 0;
  // joint: the joint stage casts again and exports the GeoTIFF once at its end.
  const bool joint_follows = options.variant == "joint" && options.until != "products";
  // With a refinement to follow, the GeoTIFF is exported once, from the
  // last cast's ENVI ortho-image.
  const MeshRayCaster mesh(ply.vertices, ply.triangles);
  out << "products: mesh read and its BVH built in "
      << std::chrono::duration<double>(std::chrono::steady_clock::now() - mesh_start).count() << " s ("
      << ply.triangles.size() << " triangles; read " << read_mesh_s << " s)\n";
  // Without a refinement this cast is the last: the RGB ortho-image (on its
  // grid) is rendered alongside its tiles, which wait on the disk, and its
  // log follows the cast's.
  std::future<std::string> rgb_ortho;
  auto startRgbOrtho = [&](const OrthoGrid& grid) {
    rgb_ortho = std::async(std::launch::async, [&, grid] {
      std::ostringstream log;
      writeRgbOrthoProducts(ply, mesh, grid, projection, options, log);
      return log.str();
    });
  };
  // The point cloud from the final line poses: after the refinement's last
  // cast when one follows (the joint stage writes it again each round).
  HyperspectralReport report =
      castProducts(survey, line_poses, mesh, projection, options,
                   options.geotiff && !refine && !joint_follows, out, !refine,
                   refine ? std::function<void(const OrthoGrid&)>{} : startRgbOrtho);
  if (refine) {
    refineExtrinsic(survey, line_poses, mesh, projection, options, report, out);
    if (options.geotiff) {
      const auto start = std::chrono::steady_clock::now();
      report.ortho_tif = options.out / "hyperspectral/ortho.tif";
      exportEnviToCog(report.ortho_hdr, report.ortho_tif, HyperspectralOptions{}.geotiff);
      out << "products: GeoTIFF written in "
          << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
    }
  }
  out << "wrote " << report.ortho_hdr.string();
  for (const fs::path& path : {report.ortho_tif, report.quicklook_png, report.ancillary_hdr}) {
    if (!path.empty()) out << ", " << path.string();
  }
  if (options.points) out << ", " << (options.out / "hyperspectral/points.ply").string();
  out << "\n";

  if (rgb_ortho.valid()) {
    out << rgb_ortho.get();
  } else {
    writeRgbOrthoProducts(ply, mesh, report.grid, projection, options, out);
  }
}

}  // namespace hsmap
