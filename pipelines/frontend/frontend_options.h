#pragma once
// FrontendOptions: every knob of the monocular visual front-end
// (docs/FRONTEND.md), with its default and validate().
//
// Units. Image-processing sizes (the KLT window, the corner grid, distances
// between corners) and pixel error thresholds are given for a reference image
// `reference_width_px` (960) pixels wide and scaled to the survey's image:
// sizes by width / reference_width_px (a 1920-wide image gets a window twice
// as wide, a 320-wide one a third of it, never below a floor), error
// thresholds by max(1, width / reference_width_px), because the measurement
// noise of a tracked corner does not shrink below a fraction of a pixel on a
// small image. Geometric thresholds (parallax, triangulation angles) are
// angles, independent of the image. Nothing here is tuned to a simulator
// preset: the defaults are those of a 25 Hz down-looking camera, and every
// decision is taken on angles or fractions that hold for other speeds,
// altitudes and sizes.

#include <string>

namespace hsmap {

struct FrontendOptions {
  // ---- image ---------------------------------------------------------------
  // Pixel sizes below are for an image this wide (see the header comment).
  double reference_width_px = 960.0;
  // Contrast-limited adaptive histogram equalisation before tracking. Lamps
  // light the seabed unevenly (bright centre, dark corners, falling off with
  // altitude); CLAHE equalises the local contrast so corners are found and
  // tracked in the dim corners too, and makes KLT less sensitive to the
  // brightness change of a point crossing the lamp's beam.
  bool use_clahe = true;
  double clahe_clip_limit = 2.0;
  int clahe_tiles_across = 8;  // tiles across the width; rows keep them square
  // Lamp light removed before CLAHE and tracking (lamp_light_field.h): each
  // frame is divided by the lamps' light pattern, estimated as the blurred
  // mean of frames sampled over the survey. Without it the tracks fall short
  // of the motion where the light falls off, and the trajectory's scale
  // drifts along the track.
  bool correct_lamp_light = true;
  int lamp_light_frames = 200;       // frames sampled evenly over the survey
  int lamp_light_min_frames = 30;    // fewer usable frames: no correction (the mean would keep texture)
  double lamp_light_blur_px = 8.0;   // Gaussian sigma at the reference width
  // Automatic gain (or exposure) steps compensated before tracking
  // (exposure_compensation.h): the relative gain between the last frame and
  // the next is measured on the tracks' surroundings, and when it differs
  // from 1 by at least `gain_compensation_min_db` and by at least 3 times its
  // own 1-sigma, the next frame is brought to the last one's exposure before
  // CLAHE and KLT. Below that the step is within the noise of the estimate
  // (about 0.02 dB on 400 tracks) or too small to matter to KLT.
  bool compensate_gain = true;
  double gain_compensation_min_db = 0.2;
  // A frame is "without usable texture" (a loss, not tracked) when the
  // standard deviation of its grey levels is below this (8-bit DN): black,
  // uniformly blurred into a wash, or a lens covered by silt.
  double min_contrast_dn = 3.0;
  // ... or when more than this fraction of its pixels is saturated (>= 250 DN).
  double max_saturated_fraction = 0.5;
  // ... or when fewer corners than this can be found in it (after a loss).
  int min_corners = 40;

  // ---- tracking (KLT) --------------------------------------------------------
  // Square window at the reference width; odd, >= 9 after scaling. Small:
  // light fixed in the image (lamps, CLAHE's tiles) pulls a window back by a
  // little every frame, the more the larger it is, and the bundle
  // adjustments turn that into a scale drifting along the track (docs/FRONTEND.md,
  // "Window size").
  int klt_window_px = 9;
  int klt_pyramid_levels = 3;       // levels above the full image
  int klt_max_iterations = 10;
  double klt_epsilon = 0.03;        // pixel change that ends a KLT iteration
  // Forward-backward check: a point tracked to the next image and back must
  // land within this of where it started.
  double forward_backward_max_px = 1.0;

  // ---- corners on a grid -------------------------------------------------------
  int grid_cells_across = 16;        // cells across the width; rows keep them square
  int max_corners_per_cell = 3;      // new corners only where a cell has fewer tracks
  double min_corner_distance_px = 12.0;
  double corner_quality = 0.01;      // Shi-Tomasi: fraction of the best corner's response

  // ---- initialisation -----------------------------------------------------------
  int init_min_tracks = 60;              // tracks from the reference frame still alive
  double init_min_parallax_deg = 2.0;    // median triangulation angle of the start
  int init_min_landmarks = 50;           // landmarks the start must triangulate
  double init_min_cheirality_fraction = 0.9;  // of the RANSAC inliers, in front of both views
  // A reference frame older than this (frames) is replaced by the current one:
  // its tracks have drifted out of view or the scene does not initialise.
  int init_max_reference_age = 60;
  double ransac_threshold_px = 1.0;      // 5-point RANSAC (Sampson distance)

  // ---- frame pose -----------------------------------------------------------
  double pnp_threshold_px = 2.0;         // PnP RANSAC inlier threshold
  int pnp_ransac_iterations = 100;
  int min_pose_inliers = 20;             // fewer after refinement: the frame is not posed
  double pixel_sigma_px = 1.0;           // noise of a tracked corner, for the solves
  double huber_scale = 2.0;              // robust loss scale, in sigmas
  int refine_max_iterations = 5;         // motion-only Levenberg-Marquardt iterations
  double inlier_threshold_px = 2.5;      // reprojection error that keeps a track's landmark

  // ---- keyframes ------------------------------------------------------------
  // A frame becomes a keyframe when the median triangulation angle of its
  // landmarks against the last keyframe exceeds this ...
  double keyframe_parallax_deg = 2.5;
  // ... or fewer than this fraction of the last keyframe's landmarks are tracked ...
  double keyframe_min_tracked_fraction = 0.6;
  // ... or fewer than this fraction of the grid's cells hold a tracked landmark
  // (the view moved onto new ground that has no landmarks yet).
  double keyframe_min_coverage = 0.5;
  int keyframe_min_interval = 2;         // frames between keyframes, at least

  // ---- landmarks ------------------------------------------------------------
  double min_triangulation_angle_deg = 1.5;  // between the two most separated rays
  double max_triangulation_error_px = 2.0;   // reprojection in every view

  // ---- local bundle adjustment ---------------------------------------------
  int ba_window_keyframes = 7;    // keyframes optimised; older ones that see them held fixed
  int ba_max_fixed_keyframes = 6; // at most this many fixed keyframes (the newest of them)
  int ba_max_iterations = 5;
  int ba_every_keyframes = 1;     // run after every n-th keyframe
  double ba_outlier_px = 3.0;     // an observation beyond this after the solve is removed

  // ---- tracking loss and segments ---------------------------------------------
  // Frames a lost track may be bridged over (KLT from the last posed frame,
  // the motion model's prediction as the start) before the segment ends and
  // tracking re-initialises.
  int max_bridged_frames = 3;
  int min_tracked_points = 30;    // fewer tracks: the frame is not posed
  int min_segment_keyframes = 4;  // a segment needs this many keyframes to be fitted to the INS
  // Segments are joined to earlier ones by vision where their views overlap
  // (segment_joiner.h); off: every segment goes through the INS.
  bool join_segments_by_vision = true;
  int join_min_inliers = 20;      // verified landmark pairs a vision join needs
  // A segment linked through the INS keeps its own fit's scale only when that
  // scale's 1-sigma is at most this fraction; otherwise the reference's.
  double max_ins_scale_sigma = 0.10;

  // ---- run ------------------------------------------------------------------
  int prefetch_frames = 8;        // decoded frames queued ahead of tracking (bounded memory)
  int solver_threads = 1;         // Ceres threads (decoding takes the other core)
  // Frames [first_frame, last_frame] are processed; -1: to the end.
  int first_frame = 0;
  int last_frame = -1;

  // Throws std::invalid_argument naming the first bad field, its value and
  // what is allowed.
  void validate() const;

  // Scale factors for an image `width_px` wide (see the header comment).
  double sizeScale(int width_px) const { return width_px / reference_width_px; }
  double errorScale(int width_px) const;
};

}  // namespace hsmap
