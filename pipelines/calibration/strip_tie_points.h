#pragma once
// Cross-modal tie points in the push-broom strip itself (render and
// compare): with the current estimate (the scan lines' poses, the RGB
// frames' poses, the surface), every UHI pixel's ray is cast onto the
// surface and the hit is coloured from the RGB frame nearest in time to the
// line (the frame whose pose relative to the UHI is the least affected by
// the trajectory's errors). That predicted strip, lines x samples in the
// UHI's own geometry, is matched against the real strip (the cube through
// the band combination fitted to the RGB luminance, ortho_luminance.h)
// patch by patch with band-passed NCC. A match of the real patch centred on
// (line, sample) at shift (dl, ds) in the prediction says: the real pixel
// (line, sample) saw the surface point that the current estimate puts at
// (line + dl, sample + ds): where the ray of that position (the pose
// interpolated between lines) meets the surface. It becomes an
// ExtrinsicTiePoint (the UHI pixel, that point; hyper_col_row and
// rgb_col_row hold the real and predicted strip positions) for the joint
// problem.
//
// Why in the strip and not between ortho-images: across the track a UHI
// pixel covers about 1 mm at 1.5 m and an RGB pixel about 2 mm, where the
// ortho-images are resampled to 1 cm; matching at the sensors' own
// resolution measures the cross-track position of a tie several times more
// precisely. Along the track both strips are sampled at the lines' spacing
// (about 14 mm on the presets), which line_phases subdivides (below).
//
// Geometry of the strip: column c averages UHI samples
// [c * sample_step, (c + 1) * sample_step) (real and predicted alike) and
// its pixel is the samples' mean, c * sample_step + (sample_step - 1) / 2;
// row i is the i-th posed line. Pixel sizes on the ground (medians over the
// strip) turn the band-pass, given in metres, into pixels per axis.
//
// The search covers +-search_lines x +-search_columns around the
// prediction: the estimate must already be within a few centimetres (the
// ortho-image matching's coarse-to-fine step reaches from far guesses;
// docs/JOINT.md says how the joint stage uses both).
//
// Patches do not overlap (the lattice's spacing is the patch size), so the
// tie points do not share pixels (the errors they share come from the
// poses and the surface the prediction is made from).
//
// Memory: the real strip and line_phases predictions (4 bytes per column
// each, and 5 for each band-passed copy with its mask) and one surface
// point per column (12 bytes): about 60 bytes per column at 4 phases,
// 0.4 GB for the 7,500 lines of 960 columns of a 100 m transect (below
// the joint solve's own peak there).

#include <Eigen/Core>
#include <cstdint>
#include <iosfwd>
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3.h"
#include "core/io/envi_reader.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "core/survey/rgb_frame_source.h"
#include "pipelines/calibration/extrinsic_tie_point.h"

namespace hsmap {

struct StripTiePointOptions {
  int sample_step = 2;       // UHI samples averaged into one strip column, >= 1
  int patch_lines = 15;      // patch height (lines), >= 3
  int patch_columns = 63;    // patch width (strip columns), >= 3
  int search_lines = 3;      // +- lines searched around the prediction, >= 1
  int search_columns = 16;   // +- columns searched, >= 1
  double blur_sigma_m = 0.002;     // band-pass on the ground: blur ...
  double highpass_sigma_m = 0.06;  // ... minus a blur of this sigma (shading)
  double min_ncc = 0.7;
  double min_peak_margin = 0.1;
  double exclusion_radius_m = 0.01;  // second peaks farther than this (on the ground) count
  double min_template_std = 0.25;    // of the real strip's standard deviation
  double frame_margin_px = 2.0;      // RGB samples this far inside the image
  // The prediction is also rendered between the lines, at line_phases
  // evenly spaced phases of the line spacing (the poses interpolated), and
  // searched at all of them: the shift along the track is then found on a
  // grid 1 / line_phases of a line fine before its sub-pixel refinement.
  // Along the track the strips are sampled every 14 mm or so; on the
  // lines alone the sub-pixel peak is pulled towards whole lines.
  int line_phases = 4;
  // Runs of at most this many unusable columns in a row of the real strip
  // (a dead or saturated sample, a pixel equal to the cube's data ignore
  // value) are interpolated from the valid columns on both sides before
  // matching: a patch must be valid throughout, so a dead sample column
  // would otherwise remove every patch across it, and a few scattered bad
  // pixels most of the strip's patches. 0: none filled.
  int fill_invalid_columns = 2;

  // std::invalid_argument naming the field and what is allowed.
  void validate() const;
};

// What the stage needs: the cube and its band combination, the current
// poses and surface. Pointers must outlive the call.
struct StripTiePointInputs {
  const EnviReader* cube = nullptr;
  std::vector<double> band_weights;  // one per band (BandCombination::weights)
  double band_offset = 0.0;
  const PushbroomCamera* uhi_camera = nullptr;
  std::vector<LinePose> lines;  // posed scan lines, cube line index and T_W_U, in line order
  const MeshRayCaster* mesh = nullptr;
  const RgbFrameSource* frames = nullptr;
  const PinholeRadtanCamera* rgb_camera = nullptr;
  // Posed frames: index into `frames` and T_W_C, in time order.
  std::vector<std::pair<int, SE3d>> frame_poses;
};

struct StripTiePointCounts {
  int patches = 0;     // on the lattice, with every pixel valid in both strips
  int textured = 0;    // real patch textured enough to match
  int matched = 0;     // confident, unambiguous NCC peak
  int tie_points = 0;  // with a surface point interpolated at the match
  int frames_decoded = 0;
  int frames_undecodable = 0;  // InputError from the frame source: their lines predict nothing
  std::int64_t filled_pixels = 0;  // real strip pixels interpolated (fill_invalid_columns)
  double across_pixel_m = 0.0;  // median strip pixel on the ground, across the track
  double along_pixel_m = 0.0;   // and along it (line spacing)
};

struct StripTiePoints {
  std::vector<ExtrinsicTiePoint> tie_points;
  StripTiePointCounts counts;
};

// Throws std::invalid_argument for missing inputs or a band_weights size
// other than the cube's bands.
StripTiePoints findStripTiePoints(const StripTiePointInputs& inputs,
                                  const StripTiePointOptions& options, std::ostream& log);

}  // namespace hsmap
