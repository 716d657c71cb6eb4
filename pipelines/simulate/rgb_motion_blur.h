#pragma once
// Motion blur of the RGB camera: the exposure integrates the image over the
// camera's motion during `exposure_s` (SimulatedRgbConfig::exposure_s).
//
// The integral is approximated by N sub-frames at the midpoints of N equal
// parts of the exposure, centred on the frame's time t (so the frame's truth
// pose stays T_W_C(t)):
//   t_i = t - T/2 + (i + 1/2) T / N,   i = 0 .. N-1,
// rendered without noise and averaged (a box filter in time: a global shutter
// open for T). N follows from how far the image moves during the exposure,
// so that neighbouring sub-frames are at most kMaxSubframeStepPx apart in the
// image and the average is a smooth streak rather than N ghost copies (the
// renderer's anti-aliasing filter is about one pixel wide; half a pixel
// between copies leaves no visible steps):
//   N = clamp(ceil(motion_px / kMaxSubframeStepPx), 1, kMaxSubframes),
// where motion_px is the largest image displacement between the exposure's
// first and last instants of the scene points seen at a 3 x 3 grid of pixels
// (each cast onto the scene from the start pose, projected from the end pose;
// translation, rotation and the scene's depth all count). A still camera or
// T = 0 gives N = 1: the frame is the instantaneous render.
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"
#include "core/raycast/mesh_ray_caster.h"

namespace hsmap {

inline constexpr double kMaxSubframeStepPx = 0.5;
inline constexpr int kMaxSubframes = 64;

// The largest image displacement (pixels) between T_W_C_begin and T_W_C_end
// of the scene points seen at a 3 x 3 grid of pixels; 0 when no ray hits.
double imageMotionPx(const PinholeRadtanCamera& camera, const MeshRayCaster& scene,
                     const SE3d& T_W_C_begin, const SE3d& T_W_C_end);

// N for an image motion of `motion_px` during the exposure (rule above).
int motionBlurSubframes(double motion_px);

// The N sub-frame times of the exposure of length `exposure_s` centred on `t`.
std::vector<double> subframeTimes(double t, double exposure_s, int subframes);

}  // namespace hsmap
