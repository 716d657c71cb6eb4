#pragma once
// The `planar` variant's flat seabed: its depth estimated from the survey
// without any mesh, and the plane z_W = depth as a mesh to cast scan lines on.
//
// Why it must be estimated. The surveys carry no altimeter: the INS gives the
// vehicle's depth, not its height above the seabed. The RGB images do, up to
// scale, and the INS gives that scale over a baseline.
//
// Method (two-view triangulation of RGB frame pairs):
//  1. Anchors: `anchor_frames` frames spread evenly over the frames that lie
//     within the INS fixes' time span.
//  2. Partner: for each anchor, a frame ahead on a ladder of frame offsets
//     (1, 2, 3, 4, 6, 8, 12, 16, 24, ...): the ladder starts at the previous
//     anchor's offset, climbs while the pairs pass with at least twice
//     `min_inliers`, and steps down when the start fails, so the partner is
//     the farthest that still overlaps well at a cost of two or three pair
//     matchings per anchor. A pair passes with: ORB features (OpenCV) matched
//     with Lowe's ratio test, the matched pixels undistorted through
//     survey.config.rgb.camera (pinhole-radtan); at least `min_inliers`
//     inliers of the relative pose below, in front of both cameras; a median
//     parallax of `min_parallax_deg`; a visual baseline direction within
//     `max_direction_error_deg` of the INS one.
//  3. Relative pose. The rotation R_C2_C1 is the planar poses' and only the
//     baseline direction t comes from the images: the epipolar constraint is
//     linear in t, two matches give it, RANSAC over such pairs
//     (`ransac_threshold_px` from the epipolar line) and a least-squares
//     refinement on the inliers. With INS attitude (~0.05 deg) that is all.
//     This is what makes a flat seabed work: its essential matrix is
//     ambiguous (a plane admits two (R, t), one with t along the plane's
//     normal; Longuet-Higgins 1984), and on the simulated flat survey most
//     cv::findEssentialMat + cv::recoverPose pairs took the wrong one (3 of
//     20 anchors passed the direction check, against 19 of 20 now). Without
//     INS attitude the planar rotation (level, along the track) is off by the
//     vehicle's roll and pitch changes, so the RANSAC runs at 5x the
//     threshold and R and t are then refined together by Gauss-Newton on the
//     Sampson distances from that start, which stays clear of the second
//     solution (measured: 19 of 20 pairs, 9 cm deeper than the truth on the
//     flat and low-relief surveys with their attitude columns removed,
//     against +4 and -1 cm with them).
//  4. Triangulation of the inliers (cv::triangulatePoints) in the anchor
//     camera C1, with the unit baseline.
//  5. Scale: the length of the camera's baseline between the two frame times
//     from the INS. Raw 1 Hz fixes with ~0.3 m of horizontal noise cannot give
//     a ~1 m baseline, so the body track is smoothed: per axis, a least-squares
//     polynomial of degree `ins_fit_degree` in (t - t_m) through the fixes
//     (insFixesInWorld, as geo-referencing converts them) within
//     +-`ins_half_window_s` of the pair's mid time t_m (a lower degree when
//     the window holds fewer than three fixes per coefficient). The camera's
//     baseline adds the lever arm:
//       c_W(t) = p_W_B(t) + R_W_B(t) t_B_C,  R_W_B(t) = R_W_C(t) R_B_C^T,
//     with R_W_C(t) the planar poses' attitude. Approximation: the vehicle's
//     position is a low-degree polynomial in time over the window (its speed
//     changes slowly).
//  6. Depth: each point p_W = c_W(t1) + R_W_C1 s X_C1 through the anchor's
//     planar pose T_W_C1 (its depth is the INS depth, +-2 cm). Only points
//     below the camera count. Per pair: its seabed z = z_C1 + median of
//     (z_point - z_camera), its altitude that median. The estimate: the median
//     over pairs of their seabed z (and of their altitudes); spread_m is the
//     median absolute deviation of the pairs' seabed z from it (unscaled).
//
// Precision. The points' median is precise to millimetres (hundreds of
// points); the error is the scale's, i.e. the smoothed INS velocity's
// relative error times the altitude. White fix noise sigma_h at rate r gives
// a velocity error of about sigma_h sqrt(12 / (N T^2)) (N fixes over T =
// 2 x half window; ~twice that at the window's ends), the INS's random-walk
// drift h' about h' sqrt(1.2 / T): with 0.33 m at 1 Hz, h' = 0.02 m/sqrt(s)
// and +-12 s, ~0.01 m/s, i.e. ~2.5% of 0.4 m/s and ~4-5 cm of a 1.7 m
// altitude per pair (1 sigma). Pairs within one window share that error, so
// the median over a 20 m survey's two or three independent windows keeps
// ~3 cm. The estimate is a median of what the camera saw; over relief it is
// the median seabed under the track, not a plane fit.
//
// Errors: std::invalid_argument for invalid options; SeabedDepthUnavailable
// when fewer than `min_pairs` pairs pass, its message naming what was missing
// (frames within the INS span, INS fixes around a pair, matches, inliers,
// parallax) so that the caller can ask for `--seabed-depth`.
//
// Time: decoding, ORB and matching of two or three frames per anchor, on
// the calling thread (the frame source is not thread-safe): 2.1-2.8 s of CPU
// for the 960x540 simulated surveys (20 anchors, ~50 pair matchings), 0.6 s
// for `tiny` (320x180), measured on a heavily loaded 2-core machine.

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/io/ply_io.h"
#include "core/survey/survey.h"
#include "pipelines/georef/georef_result.h"

namespace hsmap {

struct SeabedDepthOptions {
  int anchor_frames = 20;               // anchors spread over the survey (step 1)
  int orb_features = 1500;              // ORB features per image
  double match_ratio = 0.8;             // Lowe's ratio test on the two nearest Hamming distances
  double ransac_threshold_px = 2.0;     // RANSAC threshold: distance to the epipolar line, pixels
  int min_inliers = 40;                 // a pair passes with this many inliers in front of both cameras
  double min_parallax_deg = 1.0;        // median angle between the two rays of an inlier
  double max_direction_error_deg = 30.0;  // visual vs INS baseline direction
  double ins_half_window_s = 12.0;      // INS fixes within +- this of the pair's mid time (step 5)
  int ins_fit_degree = 2;               // polynomial degree of the smoothed track (step 5)
  int min_window_fixes = 3;             // fewer fixes in the window: the pair is skipped
  int min_pairs = 5;                    // fewer passing pairs: SeabedDepthUnavailable

  // Empty when usable, otherwise what is wrong.
  std::string validate() const;
};

struct SeabedDepthEstimate {
  double depth_m = 0.0;     // the seabed's z in W (down), metres
  double altitude_m = 0.0;  // median over pairs of the camera's height above it
  int pairs = 0;            // frame pairs that passed
  long long points = 0;     // triangulated points below the camera, over those pairs
  double spread_m = 0.0;    // median |pair seabed z - depth_m|
  double seconds = 0.0;     // wall time of the estimate

  // One line for people, e.g. "seabed at z = 40.01 m (altitude 2.00 m) from
  // 23 frame pairs, 9120 points, spread 0.012 m, 1.4 s".
  std::string summary() const;
};

// The reason the estimate could not be made (see the header comment).
class SeabedDepthUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `frames`: the planar poses (runPlanarGeoref's GeorefResult::frames), in
// time order; their `index` names the survey's frame image.
SeabedDepthEstimate estimateSeabedDepth(const Survey& survey,
                                        const std::vector<GeorefFramePose>& frames,
                                        const SeabedDepthOptions& options = {});

// The horizontal plane z_W = depth_m as a triangle mesh: a regular grid over
// the XY bounding box of `positions_W` (e.g. the frames' and scan lines'
// positions) grown by `margin_m` on every side (2 x altitude + a few metres
// covers what a camera at that altitude sees), cells of at most `cell_m`
// (1 m keeps the vertices' float coordinates fine in Embree), two triangles a
// cell with normals up (-z_W, towards the cameras), uniform grey vertex
// colours. Throws std::invalid_argument for no positions, a non-finite
// input, a negative margin or a non-positive cell.
PlyMesh flatSeabedMesh(double depth_m, const std::vector<Eigen::Vector3d>& positions_W,
                       double margin_m, double cell_m = 1.0);

}  // namespace hsmap
