// stereoPairPoints: points from a rendered pair lie on the true seabed, for
// horizontal and vertical baselines and with the reference camera on either
// side; bad options and a pair without baseline are refused.
#include "pipelines/surface/stereo_pair_points.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/raycast/mesh_ray_caster.h"
#include "pipelines/simulate/render_context.h"
#include "pipelines/simulate/rgb_renderer.h"
#include "pipelines/simulate/scene/material_field.h"
#include "pipelines/simulate/scene/seabed_scene.h"
#include "pipelines/simulate/simulation_config.h"
#include "pipelines/simulate/underwater_optics.h"

namespace hsmap {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kBaseline = 0.35;  // metres
constexpr double kAltitude = 2.0;   // metres above the mean seabed

Eigen::Quaterniond rollPitchYawDeg(double roll, double pitch, double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw * kPi / 180.0, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(pitch * kPi / 180.0, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(roll * kPi / 180.0, Eigen::Vector3d::UnitX()));
}

// A 5.5 m x 4.5 m low-relief seabed at 40 m depth and three 960x540 frames
// of the presets' camera (fx = fy = 800, mild distortion) 2 m above it,
// looking down (x_C north, y_C east, z_C down), rendered once: frame 1 is
// 0.35 m along +x_C (image right) of frame 0, frame 2 is 0.35 m along +y_C
// (image down). Frames 1 and 2 are turned by a few degrees and sit a few
// centimetres higher or lower, as keyframes of a real survey would.
struct StereoScene {
  SeabedScene scene;
  std::unique_ptr<MeshRayCaster> caster;
  PinholeRadtanCamera camera{scaledRgbCamera(960, 540)};
  std::array<SE3d, 3> T_W_C;
  std::array<cv::Mat, 3> images;

  StereoScene() {
    const SimulationConfig config = *simulationPreset("low-relief");
    SeabedSceneConfig scene_config;
    scene_config.terrain = TerrainPreset::low_relief;
    scene_config.north_min_m = -2.5;
    scene_config.north_max_m = 3.0;
    scene_config.east_min_m = -2.0;
    scene_config.east_max_m = 2.5;
    scene_config.seabed_depth_m = 40.0;
    scene_config.cell_m = 0.02;
    scene_config.seed = 7;
    scene = buildSeabedScene(scene_config);
    caster = std::make_unique<MeshRayCaster>(scene.vertices, scene.triangles);
    const MaterialField materials(3);
    const LampRig lamps(config.optics, config.calibration.T_B_C);
    RenderContext context;
    context.scene = &scene;
    context.caster = caster.get();
    context.materials = &materials;
    context.lamps = &lamps;
    context.turbidity = config.optics.turbidity;
    context.shadows = config.optics.shadows;
    context.nominal_altitude_m = kAltitude;
    SimulatedRgbConfig rgb = config.rgb;
    rgb.camera = camera.parameters();
    const RgbRenderer renderer(context, rgb, 5);

    const double z = 40.0 - kAltitude;
    T_W_C[0] = SE3d(rollPitchYawDeg(0.0, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, z));
    T_W_C[1] = SE3d(rollPitchYawDeg(1.0, -0.5, 2.0), Eigen::Vector3d(kBaseline, 0.0, z + 0.03));
    T_W_C[2] = SE3d(rollPitchYawDeg(-0.5, 1.5, -2.5), Eigen::Vector3d(0.0, kBaseline, z - 0.04));
    const SE3d T_C_B = SE3d(config.calibration.T_B_C.rotation,
                            config.calibration.T_B_C.translation_m)
                           .inverse();
    for (int k = 0; k < 3; ++k) images[k] = renderer.render(T_W_C[k] * T_C_B, T_W_C[k], k);
  }
};

const StereoScene& stereoScene() {
  static const StereoScene scene;
  return scene;
}

// Depth range of the seabed seen by frame `k` (as the sparse landmarks would
// give it), widened by 10%.
StereoPairOptions optionsFor(int k) {
  const StereoScene& s = stereoScene();
  double lo = 1e9, hi = 0.0;
  for (int v = 0; v < s.camera.height(); v += 20) {
    for (int u = 0; u < s.camera.width(); u += 20) {
      const Eigen::Vector3d ray_C = *s.camera.unproject(Eigen::Vector2d(u, v));
      const RayHit hit = s.caster->intersect(Ray{s.T_W_C[k].t, s.T_W_C[k].q * ray_C});
      if (!hit.hit()) continue;
      const double depth = hit.distance * ray_C.z();
      lo = std::min(lo, depth);
      hi = std::max(hi, depth);
    }
  }
  StereoPairOptions options;
  options.min_depth_m = lo / 1.1;
  options.max_depth_m = hi * 1.1;
  return options;
}

// Fraction of frame `ref`'s view whose seabed point lies in frame `other`'s
// image: the most that stereo can triangulate. The rectified images sample
// the undistorted view uniformly, so each pixel counts with the area it
// covers in normalised coordinates (the barrel distortion squeezes the
// image's edges, where the views do not overlap).
double overlapFraction(int ref, int other) {
  const StereoScene& s = stereoScene();
  double inside = 0.0, total = 0.0;
  auto xy = [&](double u, double v) {
    const Eigen::Vector3d ray = *s.camera.unproject(Eigen::Vector2d(u, v));
    return Eigen::Vector2d(ray.head<2>() / ray.z());
  };
  for (int v = 0; v < s.camera.height(); v += 3) {
    for (int u = 0; u < s.camera.width(); u += 3) {
      const Eigen::Vector2d xy0 = xy(u, v);
      const Eigen::Vector2d du = xy(u + 1, v) - xy0, dv = xy(u, v + 1) - xy0;
      const double area = std::abs(du.x() * dv.y() - du.y() * dv.x());
      total += area;
      const Eigen::Vector3d ray_C = *s.camera.unproject(Eigen::Vector2d(u, v));
      const RayHit hit = s.caster->intersect(Ray{s.T_W_C[ref].t, s.T_W_C[ref].q * ray_C});
      if (!hit.hit()) continue;
      const Eigen::Vector3d p_O =
          s.T_W_C[other].inverse() * (s.T_W_C[ref].t + hit.distance * (s.T_W_C[ref].q * ray_C));
      if (p_O.z() > 0.0 && s.camera.isInImage(s.camera.project(p_O))) inside += area;
    }
  }
  return inside / total;
}

struct PairAccuracy {
  double median_m = 0.0, p90_m = 0.0, valid_fraction = 0.0;
  double seconds = 0.0, cpu_seconds = 0.0;  // wall and this thread's CPU time
  double expected_sigma_m = 0.0;  // Z^2 / (f B) for 1 px of disparity
  double outlier_fraction = 0.0;  // points more than 3 px (3 expected_sigma_m) off
  StereoPairPoints points;
};

// CPU time of the calling thread: SGBM runs on it alone (MODE_SGBM), so this
// is the time of one pair on a free core even when the machine is busy.
double threadCpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double quantile(std::vector<double> values, double q) {
  const std::size_t i = std::min(values.size() - 1, std::size_t(q * values.size()));
  std::nth_element(values.begin(), values.begin() + i, values.end());
  return values[i];
}

// Runs the pair (ref, other) and measures every point's distance from the
// reference camera against the true surface along the same ray.
PairAccuracy measure(int ref, int other, const StereoPairOptions& options) {
  const StereoScene& s = stereoScene();
  PairAccuracy accuracy;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = threadCpuSeconds();
  accuracy.points = stereoPairPoints(s.images[ref], s.images[other], s.camera, s.T_W_C[ref],
                                     s.T_W_C[other], options);
  accuracy.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  accuracy.cpu_seconds = threadCpuSeconds() - cpu_start;
  const StereoPairPoints& points = accuracy.points;
  EXPECT_EQ(points.skipped, "");
  EXPECT_EQ(points.p_W.size(), points.pixel_ref.size());
  EXPECT_EQ(points.sampled_pixels,
            int(points.p_W.size()) + points.no_disparity + points.out_of_range +
                points.not_in_other);
  if (points.p_W.empty()) return accuracy;
  const Eigen::Vector3d& c_W = s.T_W_C[ref].t;
  std::vector<double> errors;
  errors.reserve(points.p_W.size());
  for (std::size_t i = 0; i < points.p_W.size(); ++i) {
    const Eigen::Vector3d to_point = points.p_W[i] - c_W;
    const RayHit hit = s.caster->intersect(Ray{c_W, to_point.normalized()});
    errors.push_back(hit.hit() ? std::abs(to_point.norm() - hit.distance) : 1e9);
    // pixel_ref is where the point projects in the reference image.
    if (i % 97 == 0) {
      const Eigen::Vector3d p_C = s.T_W_C[ref].inverse() * points.p_W[i];
      const Eigen::Vector2d pixel = s.camera.project(p_C);
      EXPECT_LT((pixel - points.pixel_ref[i].cast<double>()).norm(), 1e-3) << "point " << i;
    }
  }
  accuracy.median_m = quantile(errors, 0.5);
  accuracy.p90_m = quantile(errors, 0.9);
  const double overlap = overlapFraction(ref, other);
  accuracy.valid_fraction = double(points.p_W.size()) / (overlap * points.sampled_pixels);
  accuracy.expected_sigma_m = kAltitude * kAltitude / (points.focal_px * points.baseline_m);
  accuracy.outlier_fraction =
      double(std::count_if(errors.begin(), errors.end(),
                           [&](double e) { return e > 3.0 * accuracy.expected_sigma_m; })) /
      errors.size();
  std::printf(
      "stereo %d->%d: %s%s, %zu points of %d sampled (overlap %.0f%%, valid %.1f%% of it; "
      "%d outside the other image), search [%d, %d) px, |error| median %.1f mm, p90 %.1f mm, "
      "%.2f%% beyond 3 px (1 px = %.1f mm), %.0f ms (CPU %.0f ms)\n",
      ref, other, points.vertical ? "vertical" : "horizontal", points.flipped ? ", flipped" : "",
      points.p_W.size(), points.sampled_pixels, 100.0 * overlap, 100.0 * accuracy.valid_fraction,
      points.not_in_other,
      points.min_disparity, points.min_disparity + points.num_disparities,
      1e3 * accuracy.median_m, 1e3 * accuracy.p90_m, 100.0 * accuracy.outlier_fraction,
      1e3 * accuracy.expected_sigma_m,
      1e3 * accuracy.seconds, 1e3 * accuracy.cpu_seconds);
  return accuracy;
}

// Tolerances from the geometry: depth error = Z^2 / (f B) x disparity error,
// 14.3 mm per pixel here (Z = 2 m, f = 800 px, B = 0.35 m at downscale 1;
// twice that at downscale 0.5). SGBM's subpixel disparity on this textured
// seabed is good to a few tenths of a pixel: median below 0.25 px, 90% below
// 0.6 px (measured: 0.15 px and 0.35-0.38 px), and gross mismatches (over
// 3 px) are rare: below 1%. At least 70% of the view that both cameras see
// is triangulated (measured: 95-100%), and no more than it.
void expectAccurate(const PairAccuracy& a) {
  EXPECT_LT(a.median_m, 0.25 * a.expected_sigma_m);
  EXPECT_LT(a.p90_m, 0.6 * a.expected_sigma_m);
  EXPECT_LT(a.outlier_fraction, 0.01);
  EXPECT_GT(a.valid_fraction, 0.7);
  EXPECT_LT(a.valid_fraction, 1.03);  // 1: the overlap is estimated on another grid
}

TEST(StereoPairPoints, HorizontalBaselineReferenceOnTheLeft) {
  const PairAccuracy a = measure(0, 1, optionsFor(0));
  EXPECT_FALSE(a.points.vertical);
  EXPECT_FALSE(a.points.flipped);
  expectAccurate(a);
}

TEST(StereoPairPoints, HorizontalBaselineReferenceOnTheRightIsFlipped) {
  const PairAccuracy a = measure(1, 0, optionsFor(1));
  EXPECT_FALSE(a.points.vertical);
  EXPECT_TRUE(a.points.flipped);
  expectAccurate(a);
}

TEST(StereoPairPoints, VerticalBaselineReferenceOnTop) {
  const PairAccuracy a = measure(0, 2, optionsFor(0));
  EXPECT_TRUE(a.points.vertical);
  EXPECT_FALSE(a.points.flipped);
  expectAccurate(a);
}

TEST(StereoPairPoints, VerticalBaselineReferenceAtTheBottomIsFlipped) {
  const PairAccuracy a = measure(2, 0, optionsFor(2));
  EXPECT_TRUE(a.points.vertical);
  EXPECT_TRUE(a.points.flipped);
  expectAccurate(a);
}

TEST(StereoPairPoints, HalfSizeMatchingIsCoarserButStillOnTheSurface) {
  StereoPairOptions options = optionsFor(0);
  options.downscale = 0.5;
  const PairAccuracy a = measure(0, 1, options);
  // At half size a pixel of disparity is twice the depth (expected_sigma_m
  // already uses the halved focal length).
  EXPECT_NEAR(a.points.focal_px, 400.0, 1.0);
  expectAccurate(a);
}

TEST(StereoPairPoints, PairWithoutBaselineGivesNoPointsAndSaysWhy) {
  const StereoScene& s = stereoScene();
  const StereoPairPoints points =
      stereoPairPoints(s.images[0], s.images[1], s.camera, s.T_W_C[0], s.T_W_C[0], optionsFor(0));
  EXPECT_TRUE(points.p_W.empty());
  EXPECT_EQ(points.sampled_pixels, 0);
  EXPECT_NE(points.skipped.find("zero baseline"), std::string::npos) << points.skipped;
}

TEST(StereoPairPoints, BadInputsThrow) {
  const StereoScene& s = stereoScene();
  StereoPairOptions options = optionsFor(0);
  options.block_size = 4;
  EXPECT_THROW(stereoPairPoints(s.images[0], s.images[1], s.camera, s.T_W_C[0], s.T_W_C[1],
                                options),
               std::invalid_argument);
  cv::Mat grey;
  cv::extractChannel(s.images[1], grey, 0);
  EXPECT_THROW(stereoPairPoints(s.images[0], grey, s.camera, s.T_W_C[0], s.T_W_C[1],
                                optionsFor(0)),
               std::invalid_argument);
}

TEST(StereoPairOptions, DefaultsWithADepthRangeAreValidAndBadValuesNamed) {
  StereoPairOptions good;
  good.min_depth_m = 1.0;
  good.max_depth_m = 3.0;
  EXPECT_EQ(good.validate(), "");
  StereoPairOptions o = good;
  o.min_depth_m = 0.0;
  EXPECT_EQ(o.validate(), "min_depth_m must be finite and > 0");
  o = good;
  o.max_depth_m = 1.0;
  EXPECT_EQ(o.validate(), "max_depth_m must be finite and > min_depth_m");
  o = good;
  o.max_depth_m = std::nan("");
  EXPECT_EQ(o.validate(), "max_depth_m must be finite and > min_depth_m");
  o = good;
  o.block_size = 13;
  EXPECT_EQ(o.validate(), "block_size must be odd and in [3, 11]");
  o = good;
  o.uniqueness_ratio = -1;
  EXPECT_EQ(o.validate(), "uniqueness_ratio must be in [0, 100] (percent)");
  o = good;
  o.disp12_max_diff = 0;
  EXPECT_EQ(o.validate(), "disp12_max_diff must be >= 1 (pixels)");
  o = good;
  o.speckle_window = -5;
  EXPECT_EQ(o.validate(), "speckle_window must be >= 0 (0 turns the filter off)");
  o = good;
  o.pixel_step = 0;
  EXPECT_EQ(o.validate(), "pixel_step must be >= 1");
  o = good;
  o.downscale = 1.5;
  EXPECT_EQ(o.validate(), "downscale must be in [0.1, 1]");
}

}  // namespace
}  // namespace hsmap
