#pragma once
// The matching-free ortho-image metrics of metrics.json (DATASET.md,
// "ortho_pixel_error_m"): where each ortho pixel's content truly comes from,
// against where the pixel sits on the map.
//
// Every pixel of RUN/hyperspectral/ortho.hdr whose ancillary layer
// (RUN/hyperspectral/ancillary.hdr, same grid: band 0 the scan line, band 1
// the sample; docs/PRODUCTS.md) names a line l and a sample u shows what that
// sample of that line saw. The true seen point q_W is the first hit on the
// TRUE surface (truth/scene.ply, Embree through MeshRayCaster) of the ray of
// sample u (PushbroomCamera::unproject, with the TRUE UHI camera of
// truth/calibration.yaml: what the sample truly looked along) from the TRUE
// pose of line l (truth/uhi_poses.csv, at the line's true time). A
// fractional l or u (a gap-filled pixel, interpolated like its spectrum) is
// read between its neighbours: the pose is interpolated between lines
// floor(l) and floor(l) + 1 (interpolatePose: slerp and straight line, the
// pose at the interpolated time) and the sample goes through the camera
// model as a continuous pixel. The pixel's displacement is, horizontally
// (east, north in W),
//   d = c_W - q_W,    c_W the pixel centre taken from UTM to W
// (UtmProjection::utmToNed at down 0; exact every 16 pixels along a row and
// linear in between, as in ortho_metrics.h): where the content lies on the
// product minus where it lies in the world, the registration's sign.
//
// Patches: the ortho grid is tiled like the registration's (ortho_metrics.h,
// step 3): squares of max(min_patch_pixels, round(patch_size_m / px))
// pixels (0.3 m), the tiling centred on the raster (the margin of fewer than
// one patch at its edges is left out). A patch is MEASURED when at least
// min_measured_fraction of its pixels have a displacement; the others, and
// their pixels, are left out of both figures.
//   ortho_pixel_error_m      the best 2-D similarity S (c = s R q + t, linear
//                            least squares over every pixel of the measured
//                            patches, solved with Eigen) is removed: r = c - S q
//                            per pixel; r is averaged over each measured patch
//                            (so that the pixel's own quantisation, up to half
//                            a hit spacing, and steep flanks average out); the
//                            figure is the RMS over the patches of |mean r|:
//                            the map's distortion.
//   ortho_pixel_error_abs_m  the same with d instead of r (nothing removed):
//                            geo-referencing included.
// Both are missing, with the reason, when no patch is measured; the first
// also when the similarity is undetermined (every measured pixel sees one
// point).
//
// Speed: the ancillary layer is streamed one band of patches at a time
// (patch-side rows), the patches of a band are measured in parallel (TBB),
// each patch's rays cast as one batch (coherent neighbours: Embree's ray
// streams), each patch summed in a fixed order: the result does not depend
// on the thread count.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/geodetic_point.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3.h"
#include "core/raycast/mesh_ray_caster.h"
#include "pipelines/evaluate/metric_value.h"

namespace hsmap {

struct OrthoPixelErrorOptions {
  // The registration's patches (OrthoMetricsOptions' defaults).
  double patch_size_m = 0.3;
  int min_patch_pixels = 16;
  // A patch is measured when this fraction of its pixels has a displacement:
  // at 5 mm pixels a quarter of a 0.3 m patch is 900 pixels, enough to
  // average the quantisation out, while the swath's edges still count.
  double min_measured_fraction = 0.25;

  // std::invalid_argument naming the field when out of range.
  void validate() const;
};

struct OrthoPixelError {
  MetricValue ortho_pixel_error_m;
  MetricValue ortho_pixel_error_abs_m;

  int patch_pixels = 0;      // side of a patch in ortho pixels
  int patches = 0;           // patches tiling the ortho grid
  int patches_measured = 0;  // of those, with enough displacements
  std::int64_t pixels_named = 0;     // pixels whose ancillary names a line and sample
  std::int64_t pixels_measured = 0;  // of those, whose true ray meets the true surface
  // The removed similarity, when fitted: scale, rotation (degrees,
  // anticlockwise seen from above in (east, north)), and the mean
  // displacement over the measured patches (north, east; m).
  std::optional<double> scale;
  std::optional<double> rotation_deg;
  std::optional<Eigen::Vector2d> mean_displacement_NE;

  // One line for people: the counts and the removed similarity.
  std::string summary() const;
};

// `T_W_U_true[k]` is the true pose of scan line k, `camera_true` the true
// UHI camera, `true_scene` a caster on truth/scene.ply (in W), `origin` the
// survey origin (W's origin; the UTM zone). Throws InputError naming
// ancillary_hdr for a header without a usable UTM map info (ortho_raster_grid.h),
// fewer than 2 bands, or a pixel naming a line outside [0, lines - 1] or a
// sample outside [-0.5, samples - 0.5] (naming the first such pixel), and
// what EnviReader throws for a bad raster; std::invalid_argument for bad
// options or no line pose.
OrthoPixelError measureOrthoPixelError(const std::filesystem::path& ancillary_hdr,
                                       const std::vector<SE3d>& T_W_U_true,
                                       const PushbroomCamera& camera_true,
                                       const MeshRayCaster& true_scene, const GeodeticPoint& origin,
                                       const OrthoPixelErrorOptions& options = {});

// Why both are missing when the run has an ortho-image but no ancillary layer.
inline constexpr const char* kNoAncillaryLayer =
    "RUN/hyperspectral/ancillary.hdr not found: no scan line and sample per ortho pixel";

// On a run's files (evaluate): both missing with kNoOrthoImage
// (ortho_metrics.h) without ortho_hdr, with kNoAncillaryLayer without
// ancillary_hdr; otherwise measureOrthoPixelError after checking that the
// ancillary layer is on the ortho-image's grid (same lines, samples and map
// info; InputError naming ancillary_hdr when not).
OrthoPixelError measureRunOrthoPixelError(const std::filesystem::path& ortho_hdr,
                                          const std::filesystem::path& ancillary_hdr,
                                          const std::vector<SE3d>& T_W_U_true,
                                          const PushbroomCamera& camera_true,
                                          const MeshRayCaster& true_scene,
                                          const GeodeticPoint& origin,
                                          const OrthoPixelErrorOptions& options = {});

}  // namespace hsmap
