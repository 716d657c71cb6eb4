#pragma once
// Dense points from one pair of posed RGB keyframes: rectify the pair, run
// semi-global block matching (Hirschmüller 2008, "Stereo processing by
// semiglobal matching and mutual information", OpenCV's cv::StereoSGBM) and
// triangulate every pixel_step-th pixel of the reference image from its
// disparity.
//
// Geometry. With T_Co_Cr = T_W_Cother^-1 T_W_Cref (p_other = R p_ref + t),
// cv::stereoRectify (CALIB_ZERO_DISPARITY, alpha -1: the rectified focal
// length f is the cameras', so the rectified images keep their resolution)
// gives rotations R1, R2 into two rectified frames that differ only by a
// translation along their x axis (horizontal stereo, |t_x| >= |t_y|) or their
// y axis (vertical stereo), and P2's column 3 = f t_rect. The rectified canvas
// is then sized to hold the whole reference image (the bounding box of its
// border seen through R1, at most 1.5x the image's size per side), so no
// reference pixel is cut off whatever the in-plane rotation; both images are
// resampled onto that canvas (grey, bilinear) with the full lens model.
//
// SGBM matches along rows and wants the left image to have positive
// disparity. Vertical pairs are transposed (epipolar columns become rows);
// when the reference camera lies on the right (bottom) of the other, i.e.
// f t_rect > 0, both images are flipped left-right so the reference is the
// left image. The disparity map is always the reference's, and
// d = |u_ref - u_other| > 0 along the baseline axis, so in the rectified
// reference frame (Hartley & Zisserman, section 11.12)
//   Z = f B / d,  X = (x - cx) Z / f,  Y = (y - cy) Z / f,  B = |t_rect|,
// with (x, y) the rectified pixel (the transpose and flip undone), and
// p_ref = R1^T p_rect, p_W = T_W_Cref p_ref. The search range follows from
// the depth range: d = f B / Z_rect evaluated over a grid of reference pixels
// at min_depth_m and max_depth_m (Z_rect differs from the reference depth when
// R1 tilts), widened by 5% + 2 px and rounded up to a multiple of 16. Both
// images are padded on the left by the search range, so that reference pixels
// near the left edge keep their whole search range (OpenCV otherwise marks
// the first minDisparity + numDisparities columns invalid).
//
// Depth noise: dZ = Z^2 / (f B) dd; with SGBM's subpixel disparity noise of a
// few tenths of a pixel, Z = 2 m, f = 800 px and B = 0.35 m that is a few
// millimetres (tests/pipelines/surface/stereo_pair_points_test.cc).
//
// A point is kept when SGBM found a disparity (inside the search range,
// passing its uniqueness ratio and left-right check and the speckle filter),
// the rectified pixel looks through the reference image, the point's depth
// in the reference camera lies in [min_depth_m, max_depth_m], and the point
// projects into the other image (SGM's path aggregation otherwise carries
// disparities from the overlap into the strip only the reference sees).
//
// Errors: throws std::invalid_argument for invalid options (the validate()
// message) or images that are not 8-bit BGR of the camera's size. A pair whose
// geometry cannot give points (baseline shorter than 1e-6 of max_depth_m, a
// baseline so far along the viewing direction that the rectified reference
// view folds, a search range wider than the image) is not an error: the result
// is empty and `skipped` says why, so one bad pair does not stop a parallel
// run.
//
// Time (CPU of the calling thread, 960x540, 80 px search range, measured on
// a heavily loaded 2-core machine): 130-160 ms at downscale 1, of which SGBM
// is ~95 ms, the two rectification maps ~15 ms; ~30 ms at downscale 0.5.
// Sequential: MODE_SGBM runs on the calling thread only (MODE_SGBM_3WAY was
// ~25% cheaper but slightly less accurate and splits rows over OpenCV's
// threads); callers run pairs in parallel.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"

namespace hsmap {

struct StereoPairOptions {
  // Depth range of the scene in the reference camera (z_Cref, metres), e.g.
  // from the sparse landmarks it sees, with some margin. Sets the disparity
  // search range; points outside it are dropped. Required (no default).
  double min_depth_m = 0.0;
  double max_depth_m = 0.0;
  // SGBM's matching window (odd, 3..11): larger is smoother and more robust on
  // weak texture, smaller keeps edges. P1 = 8 block_size^2 and
  // P2 = 32 block_size^2 (OpenCV's recommendation for grey images).
  int block_size = 5;
  // Percent by which the best matching cost must beat the second best (0 off).
  int uniqueness_ratio = 10;
  // Left-right consistency: the largest difference in pixels between the
  // reference's disparity and the other image's (-1 off).
  int disp12_max_diff = 1;
  // Speckle filter: disparity blobs of fewer than this many pixels that
  // differ from their surroundings by more than 2 px are removed (0 off).
  int speckle_window = 100;
  // Keep every pixel_step-th pixel of the reference image in x and y
  // (counted in full-resolution rectified pixels).
  int pixel_step = 2;
  // Scale of the images SGBM runs on, in (0, 1]: 0.5 runs on half-size
  // images, about 4x faster, with twice the depth noise.
  double downscale = 1.0;

  // Empty when the options are usable, otherwise what is wrong.
  std::string validate() const;
};

struct StereoPairPoints {
  std::vector<Eigen::Vector3d> p_W;        // the points
  std::vector<Eigen::Vector2f> pixel_ref;  // distorted pixel of each point in the reference image

  // Counts over the sampled reference pixels (every pixel_step-th rectified
  // pixel that looks through the reference image):
  // sampled = p_W.size() + no_disparity + out_of_range + not_in_other.
  int sampled_pixels = 0;
  int no_disparity = 0;  // SGBM found no valid disparity (occlusion, no overlap, weak texture)
  int out_of_range = 0;  // disparity found, but the depth is outside the range
  int not_in_other = 0;  // disparity found, but the point falls outside the other image

  // How the pair was rectified.
  bool vertical = false;  // baseline mostly along y: images transposed for SGBM
  bool flipped = false;   // reference on the right (bottom): images flipped left-right
  double baseline_m = 0.0;
  double focal_px = 0.0;  // rectified focal length at the SGBM scale
  int min_disparity = 0;  // SGBM search range, pixels at the SGBM scale
  int num_disparities = 0;
  std::string skipped;    // non-empty: why the pair gave no points (see the header)
};

// image_ref, image_other: 8-bit BGR images (as RgbFrameSource::frame gives
// them) of the distorted camera `camera`, taken at T_W_Cref and T_W_Cother.
StereoPairPoints stereoPairPoints(const cv::Mat& image_ref, const cv::Mat& image_other,
                                  const PinholeRadtanCamera& camera, const SE3d& T_W_Cref,
                                  const SE3d& T_W_Cother, const StereoPairOptions& options);

}  // namespace hsmap
