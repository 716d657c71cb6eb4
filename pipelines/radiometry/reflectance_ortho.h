#pragma once
// The reflectance ortho-image (docs/RADIOMETRY.md; shared/DATASET.md,
// "Results folder"):
//
//   RUN/hyperspectral/reflectance.hdr/.raw   ENVI float32, the radiance ortho's grid, map info and bands
//   RUN/hyperspectral/reflectance.tif        the same as a COG (exportEnviToCog)
//
// Every ortho pixel's DN is turned into a reflectance by inverting the
// contract's model with the radiometry stage's estimate:
//
//   ρ(λ) = (DN(λ) − o(λ)) / (K(λ) · Σ_l B(θ_l) cos(i_l) / r_l² · exp(−c(λ)(r_l + r_u)))
//
// The geometry is that of the pixel's hit as the ancillary layer names it
// (scan line and sample of the hit nearest the pixel centre; a gap-filled
// pixel's fractional line is rounded, its fractional sample kept): the
// sample's ray from that line's pose T_W_U is cast onto the mesh again for
// the hit p_W and its face normal, the lamps are placed with T_W_C = T_W_U ·
// T_C_U⁻¹ (lamp_geometry.h) and a shadow ray from every lamp that faces the
// hit is cast through the mesh.
//
// NaN, counted apart in the report: a pixel the radiance ortho leaves empty;
// a pixel in a lamp's shadow (any lamp that faces the hit is hidden from it:
// the model's sum would miss that lamp's share only where the shadow is
// sharp, and its edges are not); a pixel whose correction is undetermined
// (no ancillary entry, no ray, the ray misses the mesh, no lamp faces it, or
// the ancillary range differs from the recast hit's by more than
// max_range_mismatch: a gap-filled pixel at a depth edge, where a hit of the
// near surface and one of the far surface were blended).
// Rows are read, corrected and written one at a time (two rows of the
// radiance ortho in memory), so memory does not grow with the survey.

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3.h"
#include "core/io/geotiff_export.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/lights_config.h"
#include "core/survey/pose_tables.h"
#include "core/survey/water_estimate.h"
#include "pipelines/products/scan_line_caster.h"

namespace hsmap {

struct ReflectanceOptions {
  bool write_geotiff = true;
  GeoTiffExportOptions geotiff;
  ScanLineCastOptions cast;
  // A pixel whose ancillary range (interpolated in a gap-filled pixel)
  // differs from the recast hit's by more than this fraction of it sits on a
  // depth edge: undetermined.
  double max_range_mismatch = 0.05;
  // A band whose lamp signal for a white seabed, K(λ) · Σ_l ..., is below
  // this many DN is NaN in that pixel: the water leaves less light than the
  // sensor's noise (the near infrared over metres of water), and dividing
  // the noise by it would give any reflectance.
  double min_signal_dn = 2.0;
};

struct ReflectanceReport {
  std::int64_t pixels = 0;        // of the grid
  std::int64_t empty = 0;         // empty in the radiance ortho
  std::int64_t shadowed = 0;      // in a lamp's shadow
  std::int64_t undetermined = 0;  // no geometry or no lamp facing the hit
  std::int64_t valid = 0;            // with at least one band determined
  std::int64_t dark_band_values = 0; // band values NaN in valid pixels: signal below min_signal_dn
  double seconds = 0.0;
  std::filesystem::path hdr, tif;

  std::string summary() const;
};

// From `folder`/ortho.hdr and `folder`/ancillary.hdr into
// `folder`/reflectance.hdr/.raw (+ .tif). Throws InputError for unreadable
// rasters, std::invalid_argument when the ortho's bands do not match the
// response or the estimate, or the two rasters' grids differ.
ReflectanceReport writeReflectanceOrtho(const std::filesystem::path& folder, const PushbroomCamera& camera,
                                        const std::vector<LinePose>& line_poses, const MeshRayCaster& mesh,
                                        const LightsConfig& lights, const SE3d& T_C_U,
                                        const std::vector<double>& response_dn, const WaterEstimate& water,
                                        const ReflectanceOptions& options = {});

}  // namespace hsmap
