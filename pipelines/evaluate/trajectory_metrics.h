#pragma once
// The trajectory metrics of metrics.json (DATASET.md, docs/EVALUATE.md), on
// rows already matched (input_consistency.h): frame i of the run with frame i
// of the truth, scan line k with scan line k.
//
//   rgb_ate_m            sqrt(mean_i |p_W_C_est(i) - p_W_C_true(i)|^2): no alignment, so
//                        geo-referencing errors (placement and scale) count in full.
//   rgb_ate_aligned_m    the same after the best similarity S_true_est (Umeyama:
//                        min sum_i |p_true(i) - (s R p_est(i) + t)|^2): the shape alone.
//   rgb_scale_error      |s - 1| of that similarity.
//   uhi_position_rmse_m  RMS over scan lines of |S p_W_U_est(k) - p_W_U_true(k)|, with the
//                        frames' S (not a new fit: the UHI poses are judged in the frame
//                        that the RGB trajectory defines, beyond geo-referencing).
//   uhi_rotation_rmse_deg  RMS over scan lines of the angle of R_true(k)^-1 R_S R_est(k).
//
// When the estimated frame positions are degenerate (all equal, or on one
// line to within rounding) the similarity is undetermined: the four
// alignment metrics are then missing, with alignUmeyama's reason.

#include <optional>
#include <vector>

#include "core/geometry/sim3.h"
#include "core/survey/pose_tables.h"
#include "pipelines/evaluate/metric_value.h"

namespace hsmap {

struct TrajectoryMetrics {
  MetricValue rgb_ate_m;
  MetricValue rgb_ate_aligned_m;
  MetricValue rgb_scale_error;
  MetricValue uhi_position_rmse_m;
  MetricValue uhi_rotation_rmse_deg;
  std::optional<Sim3> S_true_est;  // the frames' alignment, when it exists
};

// Frames and lines are paired by index; sizes must agree (std::invalid_argument).
TrajectoryMetrics computeTrajectoryMetrics(const std::vector<TimedPose>& frames_est,
                                           const std::vector<TimedPose>& frames_true,
                                           const std::vector<LinePose>& lines_est,
                                           const std::vector<LinePose>& lines_true);

// The rotation angle of q_a^-1 q_b in degrees, in [0, 180].
double rotationAngleDeg(const Eigen::Quaterniond& q_a, const Eigen::Quaterniond& q_b);

}  // namespace hsmap
