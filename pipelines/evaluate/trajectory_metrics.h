#pragma once
// The trajectory metrics of metrics.json (DATASET.md, docs/EVALUATE.md), on
// rows already matched (input_consistency.h): frame i of the run with frame i
// of the truth, scan line k with scan line k.
//
//   rgb_ate_m            sqrt(mean_i |p_W_C_est(i) - p_W_C_true(i)|^2): no alignment, so
//                        geo-referencing errors (placement and scale) count in full.
//   rgb_ate_aligned_m    the same after the best similarity S_true_est of the frame
//                        POSITIONS (Umeyama: min sum_i |p_true(i) - (s R p_est(i) + t)|^2):
//                        the shape alone.
//   rgb_scale_error      |s - 1| of that similarity.
//   uhi_position_rmse_m  RMS over scan lines of |S_v p_W_U_est(k) - p_W_U_true(k)|, with the
//                        frames' VIEW Sim(3) S_v (view_alignment.h: Umeyama over each
//                        frame's camera centre and its view point h along its optical
//                        axis; not a new fit on the lines: the UHI poses are judged in
//                        the frame that the RGB trajectory defines, beyond
//                        geo-referencing).
//   uhi_rotation_rmse_deg  RMS over scan lines of the angle of R_true(k)^-1 R_v R_est(k).
//
// When the estimated frame positions are degenerate (all equal, or on one
// line to within rounding) the positions-only similarity is undetermined:
// rgb_ate_aligned_m and rgb_scale_error are then missing, with alignUmeyama's
// reason. The view Sim(3) is not (its view points leave the line) unless the
// centres all coincide or the view distance h is missing (no true frame sees
// truth/scene.ply): the two uhi_* metrics are then missing with the reason.
//
// Positions-aligned diagnostics (an hsmap extension, docs/EVALUATE.md):
//   uhi_position_rmse_positions_aligned_m, uhi_rotation_rmse_positions_aligned_deg
//                        the two uhi_* metrics with the positions-only S_true_est
//                        instead of the view Sim(3) (what they were before the
//                        contract's view alignment).
//
// Attitude-anchored alignment (an hsmap extension, docs/EVALUATE.md, "The
// attitude-aligned mesh metrics"). Along a nearly straight track the frame
// positions barely determine the rotation about the track: Umeyama's roll
// is off by about sigma_position / (spread sqrt(N)), where spread is the
// track's standard deviation across its main direction, so millimetres of
// position error tilt everything mapped by S_true_est (the mesh) by tenths
// of a degree. The frames' orientations pin that rotation directly:
//   S_true_est_attitude  rotation R = chordal mean over the frames of
//                        R_true(i) R_est(i)^T (the rotation that turns the
//                        run's W into the truth's, as each frame sees it;
//                        chordalMeanRotation), then the scale and translation
//                        minimising sum_i |p_true(i) - (s R p_est(i) + t)|^2
//                        with R held (alignScaleTranslation);
//                        core/geometry/rotation_anchored_alignment.h.
//   alignment_cross_track_spread_m  the second-largest singular value of the
//                        centred true frame positions divided by sqrt(N): the
//                        std of the track across its main direction, i.e. how
//                        well positions alone fix the roll about the track.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/sim3.h"
#include "core/survey/pose_tables.h"
#include "pipelines/evaluate/metric_value.h"

namespace hsmap {

struct TrajectoryMetrics {
  MetricValue rgb_ate_m;
  MetricValue rgb_ate_aligned_m;
  MetricValue rgb_scale_error;
  MetricValue uhi_position_rmse_m;    // under the view Sim(3)
  MetricValue uhi_rotation_rmse_deg;  // under the view Sim(3)
  std::optional<Sim3> S_true_est;  // the frame positions' alignment, when it exists
  std::string why_no_alignment;    // why S_true_est is absent (empty when present)

  // The contract's view Sim(3) (view_alignment.h), the view distance h it
  // used (alignment_view_distance_m, an extension key) and the Umeyama fits
  // it took.
  std::optional<Sim3> S_true_est_view;
  std::string why_no_view_alignment;  // empty when S_true_est_view is present
  MetricValue alignment_view_distance_m;
  int view_alignment_iterations = 0;

  // Extension: the uhi_* metrics under the positions-only S_true_est.
  MetricValue uhi_position_rmse_positions_aligned_m;
  MetricValue uhi_rotation_rmse_positions_aligned_deg;

  // Extension (header comment): the alignment with the frames' orientations'
  // rotation, and how well the positions alone condition S_true_est.
  std::optional<Sim3> S_true_est_attitude;
  std::string why_no_attitude_alignment;  // empty when S_true_est_attitude is present
  MetricValue alignment_cross_track_spread_m;
};

// Frames and lines are paired by index; sizes must agree (std::invalid_argument).
// `view_distance_m` is h (view_distance.h: medianViewDistance over the true
// frames), or the reason there is none (the view metrics are then missing
// with it).
TrajectoryMetrics computeTrajectoryMetrics(const std::vector<TimedPose>& frames_est,
                                           const std::vector<TimedPose>& frames_true,
                                           const std::vector<LinePose>& lines_est,
                                           const std::vector<LinePose>& lines_true,
                                           const MetricValue& view_distance_m);

// The attitude-anchored S_true_est_attitude of frames paired by index (header
// comment). Throws std::invalid_argument with the reason when it is
// undetermined: the orientations cancel out, or the positions do not move
// along each other (all equal).
Sim3 alignFramesByAttitude(const std::vector<TimedPose>& frames_est,
                           const std::vector<TimedPose>& frames_true);

// sqrt of the second-largest eigenvalue of the positions' covariance (divided
// by N): the second singular value of the centred positions over sqrt(N), the
// std across the main direction. 0 for fewer than 2 positions.
double crossTrackSpread(const std::vector<Eigen::Vector3d>& positions);

// The rotation angle of q_a^-1 q_b in degrees, in [0, 180].
double rotationAngleDeg(const Eigen::Quaterniond& q_a, const Eigen::Quaterniond& q_b);

}  // namespace hsmap
