#pragma once
// The similarity that places and scales a visual map on the INS, by maximum
// likelihood with the noise survey.yaml states (solvers/similarity_fit.h):
// every fix's body position, its horizontal and depth components weighed by
// their own 1-sigma, and its attitude when ins.csv has one.
//
// The map gives the RGB camera's pose T_X_C at each fix's time; the INS
// measures the body B, T_B_C away (metres, exact). So the body position the
// map predicts is
//     p_W_B = s R p_X_C + t + R (R_X_C t_C_B),      t_C_B = translation of T_B_C^-1,
// the lever arm turning with the map but not scaled by it, and the body's
// attitude R R_X_C R_C_B.
//
// Without INS attitude. The level, along-track attitude an ROV flies near
// (ins_body_track.h) is an assumption, not a measurement: its error is a
// slow offset (a trim, a crab angle), the same at every fix, so it may count
// once for the whole survey at most (each fix's assumed attitude gets the
// sigma times sqrt(number of fixes)), and here it is ten times weaker still
// (5 degrees of level become 50): it only keeps defined what the positions
// leave free (the roll about a straight track, held by the bundle
// adjustment's level prior), and does not bend the scale. On a sloped track
// a pitch assumed 3 degrees off would otherwise be read as a few percent of
// scale (the depth change explained by tilt). The scale then comes from the
// positions, horizontal and depth, as evaluate's INS floor (which has no
// attitude term then) describes.
//
// The stated 1-sigma of the result (scale, rotation, placement) is what the
// INS allows given a map whose shape is exact: on a survey of decimetre
// fixes the map's shape is millimetres, so this is its uncertainty.

#include <vector>

#include "core/geometry/se3.h"
#include "core/geometry/sim3.h"
#include "core/survey/ins_body_track.h"
#include "pipelines/georef/ins_noise.h"
#include "solvers/similarity_fit.h"

namespace hsmap {

inline constexpr double kAssumedAttitudeWeakening = 10.0;

struct CameraAtFix {
  int fix = -1;  // index into InsBodyTrack::fixes()
  SE3d T_X_C;    // the map's camera pose at the fix's time, in the map's frame X
};

// Which parts of the INS the fit listens to: all of them, or (to state what
// each contributes) without the attitude (its fixes' attitudes then weigh
// only as the weak regulariser of an INS without attitude) or without the
// depth (the depths weigh as a horizontal position).
enum class InsParts { all, without_attitude, without_depth };

// S_W_X and its covariance. Throws std::invalid_argument with fewer than 2
// cameras (fitSimilarity).
SimilarityFit fitMapToIns(const std::vector<CameraAtFix>& cameras, const InsBodyTrack& ins,
                          const SE3d& T_B_C, const InsNoise& noise, const Sim3& start,
                          InsParts parts = InsParts::all);

}  // namespace hsmap
