#pragma once
// The surface mesh of a geo-referenced run, the way the surface stage makes
// it (docs/SURFACE.md), as one function that the surface and joint stages
// both call (the joint stage meshes again from its own trajectory):
//
//   SurfaceMode::dense    stereo depth maps of the keyframes, fused, meshed
//                         tile by tile (Delaunay + visibility cut) and stitched
//   SurfaceMode::sparse   the adjusted landmarks alone (the reference paper's
//                         way), not cleaned
//   SurfaceMode::flat     the planar variant: a horizontal plane at the seabed
//                         depth, given or estimated from RGB frame pairs scaled
//                         by the INS (flat_seabed.h)
//
// Progress and the reconstruction's report go to `out`.

#include <iosfwd>
#include <optional>

#include "core/io/ply_io.h"
#include "core/survey/survey.h"
#include "pipelines/georef/georef_result.h"

namespace hsmap {

enum class SurfaceMode { dense, sparse, flat };

const char* toString(SurfaceMode mode);

// `seabed_depth_m` (z in W, metres down) is read by SurfaceMode::flat only:
// estimated when absent.
PlyMesh meshSurface(const Survey& survey, const GeorefResult& georef, SurfaceMode mode,
                    std::optional<double> seabed_depth_m, std::ostream& out);

}  // namespace hsmap
