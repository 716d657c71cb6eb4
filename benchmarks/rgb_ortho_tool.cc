// rgb_ortho_tool: measures the RGB ortho-image (pipelines/products/rgb_ortho.h)
// of a run's mesh, on the grid of `--pixel` covering the whole mesh (what the
// hyperspectral ortho-image's grid is at most). Run it under /usr/bin/time -v
// for the peak memory of the whole process.
//
//   rgb_ortho_tool MESH.ply OUT_FOLDER --lat 43 --lon 5 [--depth 0] [--pixel 0.005]
//       [--band-pixels N] [--no-png] [--no-tif] [--no-overviews]
//
// The origin is the survey's (survey.yaml `origin`). Prints the grid, the
// times of reading, of the covering grid and of writeRgbOrtho, and its summary().

#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "core/geometry/utm_projection.h"
#include "core/io/ply_io.h"
#include "pipelines/products/rgb_ortho.h"

int main(int argc, char** argv) {
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); };
  CLI::App app("rgb_ortho_tool: the RGB ortho-image of a mesh, timed");
  std::string mesh_path, out_folder;
  hsmap::GeodeticPoint origin;
  double pixel_m = 0.005;
  hsmap::RgbOrthoOptions options;
  bool no_png = false, no_tif = false, no_overviews = false;
  app.add_option("mesh", mesh_path, "mesh.ply with vertex colours")->required();
  app.add_option("out", out_folder, "output folder")->required();
  app.add_option("--lat", origin.lat_deg, "survey origin latitude (deg)")->required();
  app.add_option("--lon", origin.lon_deg, "survey origin longitude (deg)")->required();
  app.add_option("--depth", origin.depth_m, "survey origin depth (m)");
  app.add_option("--pixel", pixel_m, "pixel size (m)");
  app.add_option("--band-pixels", options.band_pixels, "pixels rendered at once");
  app.add_flag("--no-png", no_png, "do not write the PNG");
  app.add_flag("--no-tif", no_tif, "do not write the GeoTIFF");
  app.add_flag("--no-overviews", no_overviews, "no GeoTIFF overviews");
  CLI11_PARSE(app, argc, argv);
  options.write_png = !no_png;
  options.write_geotiff = !no_tif;
  options.geotiff_overviews = !no_overviews;
  try {
    Clock::time_point start = Clock::now();
    const hsmap::PlyMesh mesh = hsmap::readPly(mesh_path);
    std::printf("read %zu vertices, %zu triangles in %.3f s\n", mesh.vertices.size(), mesh.triangles.size(),
                seconds(start));
    start = Clock::now();
    const hsmap::UtmProjection projection(origin);
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector3d& p : mesh.vertices) box.extend(projection.nedToUtm(p));
    const hsmap::OrthoGrid grid =
        hsmap::OrthoGrid::coveringUtm(box, pixel_m, projection.zone(), projection.northernHemisphere());
    std::printf("grid %d x %d pixels of %.4f m (%.1f Mpixel) in %.3f s\n", grid.cols, grid.rows, grid.pixel_m,
                double(grid.pixelCount()) * 1e-6, seconds(start));
    start = Clock::now();
    const hsmap::RgbOrthoReport report = hsmap::writeRgbOrtho(mesh, grid, projection, out_folder, options);
    std::printf("writeRgbOrtho %.3f s\n%s\n", seconds(start), report.summary().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rgb_ortho_tool: %s\n", e.what());
    return 1;
  }
  return 0;
}
