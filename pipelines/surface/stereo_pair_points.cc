#include "pipelines/surface/stereo_pair_points.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace hsmap {
namespace {

// The rectified canvas holds the reference image's border seen through R1,
// but at most this many times the image's size per side (a 45 degree
// in-plane rotation needs 1.4x the width; anything larger is a pair the
// survey should not pair).
constexpr double kMaxCanvasScale = 1.5;
// A rectified reference ray this close to the rectified image plane
// (z_rect / |ray|) means rectification turned the view by ~80 degrees or more:
// the baseline points along the viewing direction.
constexpr double kMinRectifiedZ = 0.2;
// SGBM's pre-filter clips the x-derivative to [-63, 63] (OpenCV's largest).
constexpr int kPreFilterCap = 63;
// Speckle filter: a blob is one disparity within 2 px (OpenCV scales by 16).
constexpr int kSpeckleRange = 2;

Eigen::Matrix3d toEigen(const cv::Mat& m) {
  Eigen::Matrix3d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = m.at<double>(r, c);
  return out;
}

// Principal point and size of one canvas axis: the rectified span
// [lo, hi] (normalised coordinates) at focal f, capped at `max_pixels`
// centred on the span.
void canvasAxis(double lo, double hi, double f, int max_pixels, double* c, int* pixels) {
  const int needed = int(std::ceil(f * (hi - lo))) + 1;
  if (needed <= max_pixels) {
    *pixels = needed;
    *c = -f * lo;
  } else {
    *pixels = max_pixels;
    *c = -f * 0.5 * (lo + hi) + 0.5 * (max_pixels - 1);
  }
}

}  // namespace

std::string StereoPairOptions::validate() const {
  if (!(std::isfinite(min_depth_m) && min_depth_m > 0.0))
    return "min_depth_m must be finite and > 0";
  if (!(std::isfinite(max_depth_m) && max_depth_m > min_depth_m))
    return "max_depth_m must be finite and > min_depth_m";
  if (block_size < 3 || block_size > 11 || block_size % 2 == 0)
    return "block_size must be odd and in [3, 11]";
  if (uniqueness_ratio < 0 || uniqueness_ratio > 100)
    return "uniqueness_ratio must be in [0, 100] (percent)";
  if (disp12_max_diff < 1) return "disp12_max_diff must be >= 1 (pixels)";
  if (speckle_window < 0) return "speckle_window must be >= 0 (0 turns the filter off)";
  if (pixel_step < 1) return "pixel_step must be >= 1";
  if (!(downscale >= 0.1 && downscale <= 1.0)) return "downscale must be in [0.1, 1]";
  return {};
}

StereoPairPoints stereoPairPoints(const cv::Mat& image_ref, const cv::Mat& image_other,
                                  const PinholeRadtanCamera& camera, const SE3d& T_W_Cref,
                                  const SE3d& T_W_Cother, const StereoPairOptions& options) {
  if (const std::string problem = options.validate(); !problem.empty()) {
    throw std::invalid_argument("stereoPairPoints: " + problem);
  }
  const int width = camera.width();
  const int height = camera.height();
  for (const cv::Mat* image : {&image_ref, &image_other}) {
    if (image->type() != CV_8UC3 || image->cols != width || image->rows != height) {
      throw std::invalid_argument(
          "stereoPairPoints: the images must be 8-bit BGR of the camera's " +
          std::to_string(width) + "x" + std::to_string(height) + " pixels, got " +
          std::to_string(image->cols) + "x" + std::to_string(image->rows) + " with " +
          std::to_string(image->channels()) + " channel(s) of depth " +
          std::to_string(image->depth()));
    }
  }

  StereoPairPoints result;
  // p_other = R p_ref + t: OpenCV's (R, T) from the first camera to the second.
  const SE3d T_Co_Cr = T_W_Cother.inverse() * T_W_Cref;
  result.baseline_m = T_Co_Cr.t.norm();
  if (!(result.baseline_m > 1e-6 * options.max_depth_m)) {
    result.skipped = "zero baseline: the cameras are " + std::to_string(result.baseline_m) +
                     " m apart, no parallax";
    return result;
  }

  const PinholeRadtanParameters& intrinsics = camera.parameters();
  const cv::Matx33d K(intrinsics.fx, 0.0, intrinsics.cx, 0.0, intrinsics.fy, intrinsics.cy, 0.0,
                      0.0, 1.0);
  const cv::Matx<double, 1, 5> distortion(intrinsics.distortion[0], intrinsics.distortion[1],
                                          intrinsics.distortion[2], intrinsics.distortion[3],
                                          intrinsics.distortion[4]);
  const Eigen::Matrix3d R_o_r = T_Co_Cr.rotationMatrix();
  cv::Matx33d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = R_o_r(r, c);
  const cv::Vec3d t(T_Co_Cr.t.x(), T_Co_Cr.t.y(), T_Co_Cr.t.z());
  cv::Mat R1, R2, P1, P2, Q;
  // alpha -1: no zoom, the rectified focal length is the cameras' (the
  // canvas is sized below instead of by OpenCV's alpha).
  cv::stereoRectify(K, distortion, K, distortion, cv::Size(width, height), R, t, R1, R2, P1, P2,
                    Q, cv::CALIB_ZERO_DISPARITY, -1.0);
  result.vertical = std::abs(P2.at<double>(1, 3)) > std::abs(P2.at<double>(0, 3));
  const int axis = result.vertical ? 1 : 0;
  const double f_t = P2.at<double>(axis, 3);  // f * t_rect along the baseline axis
  result.flipped = f_t > 0.0;                 // u_ref - u_other = -f t_rect / Z < 0
  const double f_full = P1.at<double>(0, 0);
  const double baseline = std::abs(f_t) / f_full;
  const Eigen::Matrix3d R_rect_ref = toEigen(R1);
  const Eigen::Matrix3d R_ref_rect = R_rect_ref.transpose();

  // ---- the rectified canvas: the whole reference image, at the SGBM scale --
  const double s = options.downscale;
  const double f = f_full * s;
  result.focal_px = f;
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  bool folds = false;
  auto addBorderPixel = [&](double u, double v) {
    const std::optional<Eigen::Vector3d> ray = camera.unproject(Eigen::Vector2d(u, v));
    if (!ray) return;  // beyond the fold of the distortion: no ray
    const Eigen::Vector3d r = R_rect_ref * *ray;
    if (r.z() < kMinRectifiedZ * r.norm()) {
      folds = true;
      return;
    }
    x_lo = std::min(x_lo, r.x() / r.z());
    x_hi = std::max(x_hi, r.x() / r.z());
    y_lo = std::min(y_lo, r.y() / r.z());
    y_hi = std::max(y_hi, r.y() / r.z());
  };
  constexpr int kBorderSamples = 64;  // per side; the border bends (distortion, rotation)
  for (int i = 0; i <= kBorderSamples; ++i) {
    const double u = -0.5 + width * double(i) / kBorderSamples;
    const double v = -0.5 + height * double(i) / kBorderSamples;
    addBorderPixel(u, -0.5);
    addBorderPixel(u, height - 0.5);
    addBorderPixel(-0.5, v);
    addBorderPixel(width - 0.5, v);
  }
  if (folds || !(x_hi > x_lo && y_hi > y_lo)) {
    result.skipped =
        "the baseline points too far along the viewing direction to rectify the pair";
    return result;
  }
  double cx = 0.0, cy = 0.0;
  cv::Size canvas;
  canvasAxis(x_lo, x_hi, f, int(std::ceil(kMaxCanvasScale * width * s)), &cx, &canvas.width);
  canvasAxis(y_lo, y_hi, f, int(std::ceil(kMaxCanvasScale * height * s)), &cy, &canvas.height);
  const cv::Matx33d K_rect(f, 0.0, cx, 0.0, f, cy, 0.0, 0.0, 1.0);

  // ---- disparity search range from the depth range -------------------------
  double d_lo = std::numeric_limits<double>::infinity(), d_hi = 0.0;
  constexpr int kRangeSamples = 16;
  for (int i = 0; i <= kRangeSamples; ++i) {
    for (int j = 0; j <= kRangeSamples; ++j) {
      const std::optional<Eigen::Vector3d> ray = camera.unproject(Eigen::Vector2d(
          (width - 1) * double(i) / kRangeSamples, (height - 1) * double(j) / kRangeSamples));
      if (!ray) continue;
      for (const double depth : {options.min_depth_m, options.max_depth_m}) {
        const double z_rect = (R_rect_ref * (*ray * (depth / ray->z()))).z();
        if (!(z_rect > 0.0)) continue;
        const double d = f * baseline / z_rect;
        d_lo = std::min(d_lo, d);
        d_hi = std::max(d_hi, d);
      }
    }
  }
  const int working_width = result.vertical ? canvas.height : canvas.width;
  result.min_disparity = std::max(0, int(std::floor(d_lo / 1.05 - 2.0)));
  result.num_disparities =
      16 * int(std::ceil((d_hi * 1.05 + 2.0 - result.min_disparity) / 16.0));
  if (!(d_hi > 0.0) || result.num_disparities < 16 ||
      result.num_disparities > working_width || result.min_disparity >= working_width) {
    result.skipped = "the disparity range [" + std::to_string(d_lo) + ", " +
                     std::to_string(d_hi) + "] px of the depth range does not fit the image";
    return result;
  }

  // ---- rectify, turn so the baseline runs along rows with ref on the left --
  const cv::Matx33d K_source(intrinsics.fx * s, 0.0, (intrinsics.cx + 0.5) * s - 0.5, 0.0,
                             intrinsics.fy * s, (intrinsics.cy + 0.5) * s - 0.5, 0.0, 0.0, 1.0);
  const int pad = result.num_disparities;  // see the header: the left columns keep their range
  auto working = [&](const cv::Mat& image, const cv::Mat& R_rect) {
    cv::Mat grey, source, map1, map2, rectified, turned, padded;
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
    if (s < 1.0) {
      cv::resize(grey, source, cv::Size(), s, s, cv::INTER_AREA);
    } else {
      source = grey;
    }
    cv::initUndistortRectifyMap(K_source, distortion, R_rect, K_rect, canvas, CV_16SC2, map1,
                                map2);
    cv::remap(source, rectified, map1, map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0);
    if (result.vertical) {
      cv::transpose(rectified, turned);
    } else {
      turned = rectified;
    }
    if (result.flipped) cv::flip(turned, turned, 1);
    cv::copyMakeBorder(turned, padded, 0, 0, pad, 0, cv::BORDER_CONSTANT, 0);
    return padded;
  };
  const cv::Mat left = working(image_ref, R1);
  const cv::Mat right = working(image_other, R2);

  const int bs = options.block_size;
  const cv::Ptr<cv::StereoSGBM> sgbm = cv::StereoSGBM::create(
      result.min_disparity, result.num_disparities, bs, 8 * bs * bs, 32 * bs * bs,
      options.disp12_max_diff, kPreFilterCap, options.uniqueness_ratio, options.speckle_window,
      kSpeckleRange, cv::StereoSGBM::MODE_SGBM);
  cv::Mat disparity;  // CV_16S, 16 x disparity; invalid: (min_disparity - 1) * 16
  sgbm->compute(left, right, disparity);

  // ---- triangulate every step-th rectified reference pixel -----------------
  const int step = std::max(1, int(std::lround(options.pixel_step * s)));
  const int min_raw = std::max(1, result.min_disparity * 16);
  const double f_b = f * baseline;
  const std::size_t expected =
      std::size_t(canvas.width / step + 1) * std::size_t(canvas.height / step + 1);
  result.p_W.reserve(expected);
  result.pixel_ref.reserve(expected);
  for (int y = 0; y < canvas.height; y += step) {
    for (int x = 0; x < canvas.width; x += step) {
      const Eigen::Vector3d xy1_rect((x - cx) / f, (y - cy) / f, 1.0);
      const Eigen::Vector3d ray_ref = R_ref_rect * xy1_rect;
      if (!(ray_ref.z() > 0.0)) continue;
      const Eigen::Vector2d pixel = camera.project(ray_ref);
      if (!camera.isInImage(pixel)) continue;  // canvas outside the reference image
      ++result.sampled_pixels;
      int x_work = result.vertical ? y : x;
      const int y_work = result.vertical ? x : y;
      if (result.flipped) x_work = working_width - 1 - x_work;
      const short raw = disparity.at<short>(y_work, x_work + pad);
      if (raw < min_raw) {
        ++result.no_disparity;
        continue;
      }
      const double z_rect = f_b * 16.0 / raw;
      const Eigen::Vector3d p_ref = z_rect * ray_ref;
      if (p_ref.z() < options.min_depth_m || p_ref.z() > options.max_depth_m) {
        ++result.out_of_range;
        continue;
      }
      // SGM's path costs carry disparities from the overlap into the strip
      // the other camera does not see (matched against its black border or
      // the padding): smooth, plausible and invented.
      const Eigen::Vector3d p_other = T_Co_Cr * p_ref;
      if (!(p_other.z() > 0.0) || !camera.isInImage(camera.project(p_other))) {
        ++result.not_in_other;
        continue;
      }
      result.p_W.push_back(T_W_Cref * p_ref);
      result.pixel_ref.emplace_back(float(pixel.x()), float(pixel.y()));
    }
  }
  return result;
}

}  // namespace hsmap
