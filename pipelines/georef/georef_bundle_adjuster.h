#pragma once
// The geo-referencing bundle adjustment: every keyframe and landmark of the
// front-end's map (already brought into W by the INS alignment), with
//   - every 2D observation as a ReprojectionFactor (Huber loss, so tracks
//     that slid onto another corner do not pull);
//   - every INS fix as an InsPositionFactor and an InsAttitudeFactor, with
//     the noise survey.yaml states. When the INS has no attitude, the
//     attitude factor holds the level, along-track attitude of
//     ins_body_track.h as a weak prior (InsNoise::assumed_*): without it a
//     nearly straight track leaves the map free to roll about the track,
//     which moves the camera by the lever arm and the seabed sideways.
//
// Fixes at their own time. A fix rarely falls on a keyframe: at 0.4 m/s a
// 20 ms mismatch is 8 mm. Each fix is attached to the keyframe K nearest in
// time in the same map segment, through the front-end's relative pose
// T_K_C(t_fix) from K to the camera at the fix time (interpolated between
// the frames around it). The factor's mounting becomes
//     T_B_K = T_B_C T_C_K(t_fix)
// (InsPositionFactor/InsAttitudeFactor with that in place of T_B_C), so the
// fix constrains the trajectory where the vehicle really was when it was
// recorded. T_K_C spans at most half a keyframe interval, so the drift of
// the front-end over it is negligible.
//
// Faulty fixes. After a solve, every fix's position residual is whitened by
// its stated sigmas; a fix beyond `fix_gate_sigmas` (5: a chi-square tail of 1e-5
// for 3 degrees of freedom) that is also the worst within two fixes either
// side (its neighbours are pulled by it) is left out and the problem is
// solved again, for at most `max_fix_rejection_rounds` rounds. Each
// rejected fix is reported with its ins.csv line and its distance from the
// adjusted track.
//
// The RGB intrinsics (survey.yaml's rgb.camera_sigma with some sigma > 0,
// docs/GEOREF.md "The RGB camera's intrinsics"): one more variable, K(0),
// [fx fy cx cy k1 k2 p1 p2 k3], shared by every observation
// (ReprojectionWithIntrinsicsFactor instead of ReprojectionFactor), with a
// prior at rgb.camera of those sigmas (PinholeIntrinsicsPriorFactor); a
// parameter whose sigma is 0 is held constant. After the last solve their
// 1-sigma comes from the marginal covariance (the landmarks' Schur
// complement), and a parameter the survey cannot separate is named: a
// correlation above `inseparable_correlation` with another estimated
// intrinsic, or a 1-sigma above `weak_fraction_of_prior` of its prior's
// (the data hardly inform it: e.g. the focal length against the scene's
// distance over a flat seabed flown level at one altitude, which scales
// the image the same way). Without sigmas the adjustment is the one it
// always was, to the bit.

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/se3.h"
#include "core/survey/camera_sigma.h"
#include "core/survey/ins_body_track.h"
#include "pipelines/georef/ins_noise.h"
#include "pipelines/frontend/visual_map.h"
#include "solvers/graph_solver.h"

namespace hsmap {

// One INS fix attached to a keyframe.
struct InsFixLink {
  int fix = -1;       // index into InsBodyTrack::fixes()
  int keyframe = -1;  // keyframe id in the map
  SE3d T_K_C;         // camera at the fix time, relative to the keyframe (W units)
};

struct GeorefBundleOptions {
  double pixel_sigma_px = 1.0;
  double huber_sigmas = 2.0;
  double fix_gate_sigmas = 5.0;
  int max_fix_rejection_rounds = 3;
  int max_iterations = 50;
  int num_threads = 0;  // 0: the process's thread budget (hsmap run --threads)
  double outlier_px = 3.0;  // observations beyond this after the solve are removed from the map
  // Estimated RGB intrinsics (see above): the warnings' thresholds.
  double inseparable_correlation = 0.95;
  double weak_fraction_of_prior = 0.5;
};

// The RGB intrinsics the adjustment estimated (rgb.camera_sigma given).
struct RgbIntrinsicsEstimate {
  PinholeRadtanParameters camera;  // survey.yaml's rgb.camera with the estimated values
  // 1-sigma, [fx fy cx cy k1 k2 p1 p2 k3]; 0 for a held parameter. Not
  // known when the covariance could not be computed (`covariance_error`).
  std::array<double, 9> sigma{};
  bool sigma_known = false;
  std::string covariance_error;
  double covariance_s = 0.0;
  // One text per parameter the survey cannot separate, e.g. "rgb_camera.fx
  // cannot be separated from rgb_camera.fy on this survey (correlation 0.97)".
  std::vector<std::string> inseparable;
};

struct RejectedFix {
  int fix = -1;
  long long line_number = 0;
  double t = 0.0;
  double offset_m = 0.0;   // distance of the fix from the track, metres
  std::string stage;       // "alignment" or "bundle adjustment"
};

struct GeorefBundleReport {
  SolveReport first_solve;
  SolveReport last_solve;
  int solves = 0;
  int keyframes = 0;
  int landmarks = 0;
  int reprojection_factors = 0;
  int position_factors = 0;
  int attitude_factors = 0;
  bool attitude_measured = true;  // false: the attitude factors are the assumed priors
  double position_correlation_factor = 1.0;
  int removed_observations = 0;
  std::vector<RejectedFix> rejected;  // in the bundle adjustment
  std::optional<RgbIntrinsicsEstimate> intrinsics;  // with rgb.camera_sigma
};

// Adjusts `map` (poses T_F_C and points p_F, here in W) in place. Keyframes
// observing no landmark and landmarks with fewer than 2 observations stay
// as they are. Throws std::runtime_error when the solve is not usable.
// `intrinsics_sigma` (survey.yaml's rgb.camera_sigma): with some sigma > 0
// the intrinsics are estimated too (report.intrinsics); absent or all 0,
// `camera` is held as given.
GeorefBundleReport adjustGeoreferencedMap(VisualMap& map, const std::vector<InsFixLink>& links,
                                          const InsBodyTrack& ins, const SE3d& T_B_C,
                                          const InsNoise& noise,
                                          const PinholeRadtanParameters& camera,
                                          const GeorefBundleOptions& options,
                                          const std::optional<PinholeRadtanSigma>& intrinsics_sigma = std::nullopt);

// The 9 intrinsics of `camera` / `sigma` in the factors' order [fx fy cx cy k1 k2 p1 p2 k3].
std::array<double, 9> rgbIntrinsicsOf(const PinholeRadtanParameters& camera);
std::array<double, 9> rgbIntrinsicsOf(const PinholeRadtanSigma& sigma);

}  // namespace hsmap
