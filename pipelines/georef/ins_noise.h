#pragma once
// InsNoise: the INS's noise as survey.yaml states it, for the stages that
// weigh INS fixes (the geo-referencing alignment and bundle adjustment, the
// map's placement, the joint problem).

#include <Eigen/Core>
#include <cmath>

namespace hsmap {

struct InsNoise {
  double sigma_horizontal_m = 0.5;  // one fix's error, as survey.yaml states it
  double sigma_depth_m = 0.05;
  // The position factors' sigmas are these times the factor (>= 1): fixes
  // whose errors are correlated in time count less together
  // (GeorefOptions::ins_correlation_time_s). The faulty-fix test uses the
  // sigmas above: it asks whether one fix is far off, not the track.
  double position_correlation_factor = 1.0;
  Eigen::Vector3d sigma_attitude_rad = Eigen::Vector3d::Constant(1e-3);
  // Without INS attitude: an ROV flies level within a few degrees, and its
  // heading follows its track within a crab angle.
  double assumed_level_sigma_rad = 5.0 * M_PI / 180.0;
  double assumed_heading_sigma_rad = 30.0 * M_PI / 180.0;
};

}  // namespace hsmap
