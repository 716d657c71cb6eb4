#pragma once
// Joining map segments by vision.
//
// After a tracking loss the front-end starts a new map segment S in a frame of
// its own (origin, orientation and scale from a new two-view start). When the
// loss is short the seabed seen just after it is nearly the seabed seen just
// before (0.3 s at 0.3 m/s moves a 1.4 m footprint by 9 cm), so the new
// segment can be put into the frame G of an earlier one exactly, by matching
// their landmarks, instead of through the INS (segment_linker.h), whose fixes
// are decimetres off and can be metres off.
//
// One join attempt is a pair of keyframes: an earlier one E (its landmarks in
// G) and a new one N (its landmarks in S).
//   1. Descriptors at the pixels of each keyframe's landmark observations,
//      on the pre-processed grey image the tracker saw, so that every
//      descriptor carries a 3-D landmark of its own segment: SIFT
//      (cv::SIFT::compute; Lowe, IJCV 2004), keypoint size 6 px, or ORB
//      (cv::ORB::compute; Rublee et al., ICCV 2011), 31 px patch. Upright
//      (angle 0): across a gap a down-looking camera turns by degrees, and
//      skipping the orientation keeps the two sides' descriptors of one
//      corner alike. SIFT's gradient histograms bear the change of shape
//      of a patch over relief seen from two directions ~25 deg apart (a 2 s
//      gap on a rugged seabed) where ORB's binary tests do not: 48 SIFT
//      matches / 44 verified against 28 ORB / none. The runner tries both
//      (frontend_runner.cc, docs/FRONTEND.md): on a new segment of few
//      keyframes the Sim(3)'s rotation is weak and which matched set
//      verifies is chance.
//   2. Matches. L2 (SIFT) or Hamming (ORB, at most max_hamming bits),
//      Lowe's ratio test (best < ratio x second best) and mutual best (N's
//      best in E and E's best in N agree).
//   3. PnP RANSAC of N on E's landmarks (estimateFramePose: cv::solvePnPRansac
//      then the motion-only refinement, the front-end's own pose code): T_G_N.
//   4. Sim(3) of the matched pairs, S landmark -> G landmark, with RANSAC
//      (alignUmeyamaRobust, core/geometry/sim3.h), the threshold a fraction of
//      the altitude (the median depth of E's matched landmarks, in G's units):
//      S_G_S, and its scale's 1-sigma (below).
//   5. Verification, each must hold:
//        - the Sim(3)'s pose of N, S_G_S * T_S_N, agrees with the PnP pose:
//          rotation within max_rotation_deg, position within
//          max_position_fraction of the altitude;
//        - the inliers (pairs inside the Sim(3)'s threshold, PnP inliers, and
//          reprojecting within max_reprojection_px in both E and N under the
//          joined map: the pair's landmark at E's position, N at S_G_S T_S_N)
//          number at least min_inliers, and are at least half of the
//          Sim(3)'s inliers (a wrong similarity that happens to gather 3-D
//          agreement does not reproject).
//
// The scale's 1-sigma is the least-squares standard error of the Sim(3)'s
// scale over the inliers (with the rotation held):
//     sigma_s = sigma / sqrt(sum_i |R (p_S,i - mean p_S)|^2),
//     sigma^2 = sum_i |p_G,i - S_G_S p_S,i|^2 / (3 n - 7),
// the per-coordinate residual variance of the fit. It treats the landmarks'
// errors as independent, which they are not quite (a segment's landmarks
// share its keyframes' errors), so it is a lower bound; the join's bundle
// adjustment then sets the scale from the observations themselves.

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"
#include "core/geometry/sim3.h"
#include "pipelines/frontend/frame_pose_estimator.h"
#include "pipelines/frontend/visual_map.h"

namespace hsmap {

struct SegmentJoinOptions {
  // Keyframes tried: the earlier segments' keyframes nearest in time to the
  // new segment's start (those before the gap, and any earlier one) ...
  // (10 keyframes before the gap reach ~1 m back at the usual spacing: the
  // pairs that overlap after a gap of up to ~2 s at 0.4 m/s)
  int earlier_keyframes = 10;
  // ... against the new segment's first keyframes.
  int new_keyframes = 6;
  // The descriptor: "sift" (default) or "orb" (the one before; fewer
  // matches across a wide baseline over relief, see the header comment).
  std::string descriptor = "sift";
  // SIFT keypoint size (pixels at the survey's image): the descriptor's
  // 4x4 cells are 3 x size/2 pixels wide, so 6 px covers ~36 px, about ORB's
  // patch. Larger supports lose matches over relief (each side sees it from
  // a different direction): on rugged after a 2 s gap, 6 px gave 4 verified
  // keyframe pairs, 8 px 3, 12 px 1, 20 px 1.
  double sift_size_px = 6.0;
  // ORB patch (pixels at the survey's image): the descriptor's support.
  int orb_patch_px = 31;
  double ratio = 0.8;        // Lowe's ratio test
  int max_hamming = 64;      // of 256 bits (ORB only)
  int min_inliers = 20;      // verified pairs a join needs
  // Sim(3) RANSAC threshold, a fraction of the altitude: the landmarks of a
  // segment's first keyframes are triangulated from ~2 deg of parallax, a
  // few percent in depth.
  double sim3_threshold_fraction = 0.05;
  double max_rotation_deg = 1.0;         // PnP vs Sim(3) pose of N
  double max_position_fraction = 0.03;   // PnP vs Sim(3) position of N, of the altitude
  double max_reprojection_px = 3.0;      // inliers in E and in N under the joined map
  PoseEstimatorOptions pnp;              // the tracker's, scaled to the image
};

// One keyframe as a join attempt needs it: its pose and its landmarks in the
// frame X of its side (G for the earlier keyframe, S for the new one).
struct JoinKeyframeView {
  int keyframe_id = -1;
  int segment = -1;
  SE3d T_X_C;
  std::vector<int> landmark_ids;          // map ids, per observation
  std::vector<Eigen::Vector3d> p_X;       // landmark positions in X
  std::vector<Eigen::Vector2d> pixels;    // observation pixels (distorted)
  cv::Mat gray;                           // the pre-processed grey image
  // Filled by describeJoinView(): descriptors (CV_8U rows) and, per row, the
  // index into landmark_ids of the observation it describes.
  cv::Mat descriptors;
  std::vector<int> described;
};

// The view of keyframe `keyframe_id` of `map`, its pose and landmarks taken
// from the map's frame into X by S_X_map (valid landmarks with at least two
// observations only).
JoinKeyframeView makeJoinView(const VisualMap& map, int keyframe_id, const Sim3& S_X_map, cv::Mat gray);

// Computes the descriptors of the view (step 1), in place.
void describeJoinView(JoinKeyframeView& view, const SegmentJoinOptions& options);

struct SegmentJoin {
  bool ok = false;
  std::string failure;  // why not (the first check that failed)
  int earlier_keyframe = -1, new_keyframe = -1;  // map keyframe ids
  int earlier_segment = -1;
  std::string descriptor;  // the options' descriptor the matches are of
  int matches = 0;       // mutual, ratio-tested descriptor matches
  int pnp_inliers = 0;
  int sim3_inliers = 0;
  int inliers = 0;       // verified pairs
  Sim3 S_G_S;            // the new segment's frame -> the earlier keyframe's frame G
  double scale_sigma = 0.0;          // 1-sigma of S_G_S.scale() (see the header comment)
  double rotation_gap_deg = 0.0;     // PnP vs Sim(3) pose of N
  double position_gap_fraction = 0.0;  // of the altitude
  double reprojection_rms_px = 0.0;  // of the inliers, over both keyframes
  double altitude = 0.0;             // median depth of E's matched landmarks, G's units
  // The verified pairs: (earlier landmark id, new landmark id).
  std::vector<std::pair<int, int>> landmark_pairs;
  // The runner's: verified keyframe pairs whose landmark pairs were merged.
  int pairs_from_keyframe_pairs = 1;
};

// Steps 2-5 on one pair of described views (earlier in G, new in S).
SegmentJoin joinKeyframePair(const JoinKeyframeView& earlier, const JoinKeyframeView& later,
                             const PinholeRadtanCamera& camera, const SegmentJoinOptions& options);

// Landmark pairs of two described views under a similarity already accepted
// (guided matching): an earlier landmark and a new one pair when the new one,
// taken into G by S_G_S, is within threshold_G of it in 3-D, each reprojects
// within options.max_reprojection_px of the other's observation (the new
// keyframe at S_G_S T_S_N), and their descriptors are each other's nearest
// among the candidates that pass these gates, at a descriptor distance at
// most twice the pairs' median (a chance neighbour is another patch). The
// accepted join ties one
// keyframe pair; these ties reach every keyframe pair that overlaps, which is
// what holds the new segment's scale along its length. (earlier, new) ids.
std::vector<std::pair<int, int>> pairsUnderSimilarity(const JoinKeyframeView& earlier, const JoinKeyframeView& later,
                                                      const PinholeRadtanCamera& camera, const Sim3& S_G_S,
                                                      double threshold_G, const SegmentJoinOptions& options);

}  // namespace hsmap
