#include "pipelines/surface/surface_meshing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>
#include <string>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/util/progress.h"
#include "pipelines/surface/dense_surface.h"
#include "pipelines/surface/flat_seabed.h"
#include "pipelines/surface/sparse_map_points.h"
#include "pipelines/surface/surface_reconstruction.h"
#include "pipelines/surface/vertex_colours.h"

namespace hsmap {

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
PlyMesh flatSurface(const Survey& survey, const GeorefResult& georef, std::optional<double> seabed_depth_m,
                    std::ostream& out) {
  double depth = 0.0, altitude = 2.0;
  if (seabed_depth_m) {
    depth = *seabed_depth_m;
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
  if (!seabed_depth_m) {
    double sum = 0.0;
    for (const auto& p : positions_W) sum += depth - p.z();
    altitude = std::max(altitude, sum / double(positions_W.size()));
  }
  return flatSeabedMesh(depth, positions_W, 2.0 * std::abs(altitude) + 2.0);
}

}  // namespace

const char* toString(SurfaceMode mode) {
  switch (mode) {
    case SurfaceMode::dense: return "dense";
    case SurfaceMode::sparse: return "sparse";
    case SurfaceMode::flat: return "flat";
  }
  return "?";
}

PlyMesh meshSurface(const Survey& survey, const GeorefResult& georef, SurfaceMode mode,
                    std::optional<double> seabed_depth_m, std::ostream& out) {
  switch (mode) {
    case SurfaceMode::flat: return flatSurface(survey, georef, seabed_depth_m, out);
    case SurfaceMode::sparse: return sparseSurface(survey, georef, out);
    case SurfaceMode::dense: break;
  }
  return denseSurface(survey, georef, out);
}

}  // namespace hsmap
