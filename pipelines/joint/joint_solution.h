#pragma once
// The joint problem's solution (joint_problem.h) turned into the run's
// files: the tie points it takes, every frame and scan line posed from its
// spline, the map for meshing again, calibration.yaml. Used by the joint
// stage (pipelines/run/joint_stage.h, docs/JOINT.md).

#include <optional>
#include <vector>

#include "core/geometry/se3.h"
#include "core/geometry/sim3.h"
#include "core/survey/pose_tables.h"
#include "core/survey/run_calibration.h"
#include "pipelines/calibration/extrinsic_tie_point.h"
#include "pipelines/georef/georef_result.h"
#include "pipelines/georef/map_placement.h"
#include "pipelines/joint/joint_problem.h"

namespace hsmap {

// Each tie point with the recorded time at its continuous line position
// (between the two lines around it); ties outside the lines are dropped.
std::vector<JointTiePoint> jointTiePoints(const std::vector<ExtrinsicTiePoint>& found,
                                          const std::vector<double>& line_times);

// The georef result with every frame and scan line posed from the spline
// where it is valid (elsewhere the sequential poses stay, the lines with the
// new extrinsic), T_C_U, d and the landmarks the joint solution's.
GeorefResult posedFromSpline(const GeorefResult& sequential, const JointResult& joint,
                             const std::vector<double>& line_times);

// The similarity G that brings the solved trajectory onto the one the
// surface was made with (least squares over the frames' positions,
// Eigen::umeyama with scale). The solve may settle the whole trajectory a
// few centimetres away and its scale a percent or two off: both are the
// INS's to decimetres and percents, and the joint problem weighs the INS
// for the trajectory's shape (its position sigmas inflated for the INS's
// correlated wander, docs/GEOREF.md), not as the maximum-likelihood
// placement georef found with the stated noise. So the solution keeps
// georef's placement and scale (the map's, whose 1-sigma map_placement.yaml
// states), and the scan lines are cast onto the mesh in the mesh's frame.
Sim3 ontoSurfaceFrame(const SE3Splined& solved, const SE3Splined& surface, const std::vector<TimedPose>& frames);

// The solution moved by G: its spline's control points (a similarity maps a
// cumulative SE(3) B-spline onto the spline of the mapped control points,
// scaling translations being an automorphism of SE(3)), its landmarks, and
// T_C_U's translation, which the tie points measured in the map's units
// (scaled by G's scale; the rotation and d do not change).
JointResult inSurfaceFrame(JointResult joint, const Sim3& G);

// The sparse map of `posed` with the joint keyframe poses and landmarks, to
// mesh again.
GeorefResult withJointMap(GeorefResult posed, const JointResult& joint);

// calibration.yaml of a joint solution found in `round`: T_C_U and d with
// their 1-sigma, the observability warnings and the solve's own.
//
// With `placement` (georef's), the lever arm's 1-sigma carries the map's
// scale uncertainty (addMapScaleUncertainty, map_placement.h): the joint
// problem's own covariance holds the tie points' millimetres, which tie
// T_C_U to the map, not to the truth.
//
// When the solution estimated the UHI intrinsics, `uhi_camera` (survey.yaml's
// camera) names the parameters: calibration.yaml gets uhi_camera with their
// 1-sigma, and a warning for each the survey cannot separate.
RunCalibration jointCalibration(const JointResult& joint, int round,
                                const std::optional<MapPlacement>& placement = std::nullopt);

}  // namespace hsmap
