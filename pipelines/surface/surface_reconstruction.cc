#include "pipelines/surface/surface_reconstruction.h"

#include <chrono>

#include "pipelines/surface/surface_extraction.h"

namespace hsmap {

SurfaceReconstruction reconstructSurface(const VisibilityPoints& points,
                                         const SurfaceCutOptions& options) {
  SurfaceCutReport report;
  CellLabelling labelling = labelCells(points, options, &report);
  const auto start = std::chrono::steady_clock::now();
  SurfaceMesh mesh = extractSurface(labelling);
  report.seconds_extraction =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report.seconds_total += report.seconds_extraction;
  report.facets_in_cut = static_cast<std::int64_t>(mesh.triangles.size());
  return {std::move(labelling), std::move(mesh), report};
}

}  // namespace hsmap
