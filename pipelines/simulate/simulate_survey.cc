#include "pipelines/simulate/simulate_survey.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <tbb/parallel_for.h>

#include "core/geometry/local_ned_frame.h"
#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/so3.h"
#include "core/io/envi_writer.h"
#include "core/io/ply_io.h"
#include "core/survey/csv_table.h"
#include "core/survey/survey_config.h"
#include "core/survey/lamp_response_csv.h"
#include "core/survey/truth_files.h"
#include "core/util/progress.h"
#include "core/util/stage_timer.h"
#include "pipelines/simulate/motion/ins_synthesis.h"
#include "pipelines/simulate/motion/vehicle_trajectory.h"
#include "pipelines/simulate/reflectance_ortho.h"
#include "pipelines/simulate/rgb_auto_gain.h"
#include "pipelines/simulate/rgb_frame_writer.h"
#include "pipelines/simulate/rgb_gain_truth.h"
#include "pipelines/simulate/rgb_motion_blur.h"
#include "pipelines/simulate/rgb_renderer.h"
#include "pipelines/simulate/scene/seabed_scene.h"
#include "pipelines/simulate/sensor_noise.h"
#include "pipelines/simulate/swath_footprint.h"
#include "pipelines/simulate/uhi_renderer.h"

namespace hsmap {
namespace {

SE3d toSe3(const RigidTransformConfig& transform) {
  return SE3d(transform.rotation, transform.translation_m);
}

RigidTransformConfig toConfig(const SE3d& T) {
  RigidTransformConfig transform;
  transform.rotation = T.q.normalized();
  transform.translation_m = T.t;
  return transform;
}

// Independent sub-seeds for the parts of the simulation, so that changing
// one part's settings does not reshuffle the others' noise.
enum SeedStream : std::uint64_t { kScene = 11, kMaterials, kMotion, kIns, kRgb, kUhi, kGuess };

std::filesystem::path targetFolder(const std::filesystem::path& folder) {
  std::filesystem::path target = std::filesystem::absolute(folder).lexically_normal();
  if (target.filename().empty()) target = target.parent_path();
  if (target.filename().empty() || target == target.root_path()) {
    throw std::invalid_argument("simulate: '" + folder.string() + "' is not a folder name");
  }
  return target;
}

// The calibration guess of survey.yaml: the truth moved by the configured
// errors, in seeded random directions.
void perturbCalibration(const SimulationConfig& config, SurveyConfig& survey) {
  SensorNoise draws(noiseSeed(config.seed, kGuess, 0));
  auto randomUnit = [&] {
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = draws.normal();  // in order: the bytes must not depend on the compiler
    return Eigen::Vector3d(v.normalized());
  };
  const SimulatedCalibrationConfig& truth = config.calibration;
  const Eigen::Vector3d axis = randomUnit();
  const Eigen::Quaterniond delta(
      Eigen::AngleAxisd(truth.error_rotation_deg * M_PI / 180.0, axis));
  survey.uhi.T_C_U.rotation = (truth.T_C_U.rotation * delta).normalized();
  survey.uhi.T_C_U.translation_m =
      truth.T_C_U.translation_m + truth.error_translation_m * randomUnit();
  survey.uhi.time_offset_s = truth.time_offset_s - truth.error_time_offset_s;
  // The UHI camera's intrinsics as a calibration in air or an old one would
  // give them (truth/calibration.yaml keeps the true uhi.camera).
  survey.uhi.camera.f *= 1.0 + truth.error_uhi_focal_rel;
  survey.uhi.camera.cx += truth.error_uhi_cx_px;
  for (std::size_t i = 0; i < 2; ++i) survey.uhi.camera.distortion[i] += truth.error_uhi_distortion[i];
  survey.uhi.camera_sigma = truth.uhi_camera_sigma;
  // The same for the RGB camera; applied only when asked, so that a survey
  // without these settings keeps its bytes (a -0 distortion stays -0).
  if (truth.error_rgb_focal_rel != 0.0) {
    survey.rgb.camera.fx *= 1.0 + truth.error_rgb_focal_rel;
    survey.rgb.camera.fy *= 1.0 + truth.error_rgb_focal_rel;
  }
  if (truth.error_rgb_cx_px != 0.0) survey.rgb.camera.cx += truth.error_rgb_cx_px;
  if (truth.error_rgb_cy_px != 0.0) survey.rgb.camera.cy += truth.error_rgb_cy_px;
  for (std::size_t i = 0; i < 5; ++i) {
    if (truth.error_rgb_distortion[i] != 0.0) survey.rgb.camera.distortion[i] += truth.error_rgb_distortion[i];
  }
  survey.rgb.camera_sigma = truth.rgb_camera_sigma;
  // Priors that do not contradict the guess: at least as wide as its error.
  survey.uhi.sigma_rotation_deg = std::max(2.0, truth.error_rotation_deg);
  survey.uhi.sigma_translation_m = std::max(0.05, truth.error_translation_m);
  survey.uhi.time_offset_sigma_s = std::max(0.05, std::abs(truth.error_time_offset_s));
}

SurveyConfig surveyConfig(const SimulationConfig& config, double duration_s,
                          const std::optional<RgbVideoConfig>& rgb_video) {
  SurveyConfig survey;
  survey.name = config.name;
  if (rgb_video) {
    survey.rgb.video = rgb_video;
  } else {
    survey.rgb.frames = "rgb/frames.csv";
  }
  survey.rgb.camera = config.rgb.camera;
  survey.uhi.cube = "uhi/cube.hdr";
  survey.uhi.lines = "uhi/lines.csv";
  survey.uhi.camera = config.uhi.camera;
  perturbCalibration(config, survey);
  survey.ins.file = "nav/ins.csv";
  survey.ins.T_B_C = config.calibration.T_B_C;
  const InsNoiseConfig& ins = config.ins;
  survey.ins.sigma_horizontal_m =
      std::max(0.01, std::hypot(ins.horizontal_noise_m,
                                ins.horizontal_drift_m_per_sqrt_s * std::sqrt(duration_s)));
  survey.ins.sigma_depth_m = std::max(
      0.005, std::hypot(ins.depth_noise_m, ins.depth_drift_m_per_sqrt_s * std::sqrt(duration_s)));
  survey.ins.sigma_attitude_deg = {std::max(0.01, ins.roll_pitch_noise_deg),
                                   std::max(0.01, ins.roll_pitch_noise_deg),
                                   std::max(0.01, ins.heading_noise_deg)};
  survey.origin = config.origin;
  return survey;
}

EnviHeader uhiCubeHeader(const SimulationConfig& config, const std::vector<double>& wavelengths) {
  EnviHeader header;
  header.samples = config.uhi.camera.samples;
  header.lines = 0;  // counted while writing
  header.bands = config.uhi.bands;
  header.data_type = EnviDataType::uint16;
  header.interleave = EnviInterleave::bil;
  header.wavelength = wavelengths;
  header.wavelength_units = "Nanometers";
  const double spacing = wavelengths.size() > 1 ? wavelengths[1] - wavelengths[0] : 2.0;
  header.fwhm.assign(wavelengths.size(), spacing);
  header.description = "hsmap simulate: UHI radiance in digital numbers";
  return header;
}

// The north/east bounding box in W of the scene's extent once turned
// (seabed_scene_config.h): the extent itself at heading 0.
struct WorldExtent {
  double north_min_m, north_max_m, east_min_m, east_max_m;
};

WorldExtent turnedSceneExtent(const SeabedSceneConfig& scene) {
  if (scene.heading_deg == 0.0) {
    return {scene.north_min_m, scene.north_max_m, scene.east_min_m, scene.east_max_m};
  }
  const double heading = scene.heading_deg * M_PI / 180.0;
  const double cos_h = std::cos(heading);
  const double sin_h = std::sin(heading);
  WorldExtent extent{1e300, -1e300, 1e300, -1e300};
  for (double north : {scene.north_min_m, scene.north_max_m}) {
    for (double east : {scene.east_min_m, scene.east_max_m}) {
      const double dn = north - scene.pivot_north_m;
      const double de = east - scene.pivot_east_m;
      const double north_W = scene.pivot_north_m + cos_h * dn - sin_h * de;
      const double east_W = scene.pivot_east_m + sin_h * dn + cos_h * de;
      extent.north_min_m = std::min(extent.north_min_m, north_W);
      extent.north_max_m = std::max(extent.north_max_m, north_W);
      extent.east_min_m = std::min(extent.east_min_m, east_W);
      extent.east_max_m = std::max(extent.east_max_m, east_W);
    }
  }
  return extent;
}

// True when the frame at `tau_s` from the trajectory's start falls in a
// configured video dropout.
bool inBlackout(const std::vector<RgbBlackout>& blackouts, double tau_s) {
  for (const RgbBlackout& blackout : blackouts) {
    if (tau_s >= blackout.start_s && tau_s < blackout.start_s + blackout.duration_s) return true;
  }
  return false;
}

}  // namespace

std::uint64_t simulationMaterialSeed(const SimulationConfig& config) {
  return noiseSeed(config.seed, kMaterials, 0);
}

std::string SimulationSummary::toString() const {
  std::ostringstream out;
  out << "simulated survey written to " << folder.string() << "\n";
  out << "  scene: " << scene_triangles << " triangles (truth/scene.ply)\n";
  out << "  rgb: " << rgb_frames << " frames of " << rgb_width << "x" << rgb_height;
  if (rgb_format == "h264") {
    char rate[96];
    std::snprintf(rate, sizeof(rate), " (rgb/video.mp4, H.264, %.1f MB, %.2f Mbit/s)\n",
                  rgb_bytes / 1e6, rgb_frames > 0 ? rgb_bytes * 8.0 * rgb_rate_hz / rgb_frames / 1e6 : 0.0);
    out << rate;
  } else {
    out << " (rgb/frames.csv, " << rgb_format << ", " << (rgb_bytes + 500000) / 1000000 << " MB)\n";
  }
  out << "  uhi: " << uhi_lines << " lines x " << uhi_samples << " samples x " << uhi_bands
      << " bands (uhi/cube.hdr, uhi/lines.csv)\n";
  out << "  ins: " << ins_fixes << " fixes (nav/ins.csv)\n";
  out << "  truth: reflectance " << reflectance_cols << "x" << reflectance_rows << " pixels, "
      << reflectance_valid_pixels << " in the UHI footprint; rgb_poses.csv, uhi_poses.csv, "
      << "calibration.yaml\n";
  char line[160];
  std::snprintf(line, sizeof(line), "  survey time: %.1f s\n", survey_seconds);
  out << line;
  double total = 0.0;
  for (const auto& [stage, seconds] : stage_seconds) {
    std::snprintf(line, sizeof(line), "  %-22s %8.1f s\n", (stage + ":").c_str(), seconds);
    out << line;
    total += seconds;
  }
  std::snprintf(line, sizeof(line), "  %-22s %8.1f s, peak memory %.0f MB\n", "total:", total,
                peak_memory_mb);
  out << line;
  return out.str();
}

SimulationSummary simulateSurvey(const SimulationConfig& config,
                                 const std::filesystem::path& folder, std::ostream& log) {
  validateSimulationConfig(config);
  const std::filesystem::path target = targetFolder(folder);
  std::filesystem::path partial = target;
  partial += ".partial";
  std::filesystem::remove_all(partial);  // left over by an interrupted run
  for (const char* sub : {"rgb", "uhi", "nav", "truth"}) {
    std::filesystem::create_directories(partial / sub);
  }

  SimulationSummary summary;
  summary.folder = target;
  StageTimings timings;

  // ---- scene -------------------------------------------------------------
  auto scene_stage = timings.stage("scene");
  const VehicleMotionConfig& motion_config = config.motion;
  const double lane_east_min = motion_config.start_east_m;
  const double lane_east_max =
      motion_config.start_east_m + (motion_config.lanes - 1) * motion_config.lane_spacing_m;
  const double half_swath = 0.8 * motion_config.altitude_m + 2.0;
  const double turn_margin = motion_config.lanes > 1 ? motion_config.lane_spacing_m : 0.0;
  SeabedSceneConfig scene_config;
  scene_config.terrain = config.scene.terrain;
  scene_config.north_min_m = motion_config.start_north_m - 3.0 - turn_margin;
  scene_config.north_max_m =
      motion_config.start_north_m + motion_config.length_m + 3.0 + turn_margin;
  scene_config.east_min_m = lane_east_min - half_swath;
  scene_config.east_max_m = lane_east_max + half_swath;
  scene_config.seabed_depth_m = config.scene.seabed_depth_m;
  scene_config.cell_m = config.scene.cell_m;
  scene_config.seed = noiseSeed(config.seed, kScene, 0);
  // The extent above is along the track as if it headed north; the scene is
  // built that way and turned about the track's start with the path.
  scene_config.heading_deg = motion_config.heading_deg;
  scene_config.pivot_north_m = motion_config.start_north_m;
  scene_config.pivot_east_m = motion_config.start_east_m;
  scene_config.slope_deg = config.scene.slope_deg;
  scene_config.slope_direction_deg = config.scene.slope_direction_deg;
  log << "scene: building " << terrainPresetName(config.scene.terrain) << " seabed, "
      << (scene_config.north_max_m - scene_config.north_min_m) << " m x "
      << (scene_config.east_max_m - scene_config.east_min_m) << " m" << std::endl;
  const SeabedScene scene = buildSeabedScene(scene_config);
  const MeshRayCaster caster(scene.vertices, scene.triangles);
  const MaterialField materials(simulationMaterialSeed(config));
  const LampRig lamps(config.optics, config.calibration.T_B_C);
  RenderContext context;
  context.scene = &scene;
  context.caster = &caster;
  context.materials = &materials;
  context.lamps = &lamps;
  context.turbidity = config.optics.turbidity;
  context.shadows = config.optics.shadows;
  context.nominal_altitude_m = motion_config.altitude_m;
  context.backscatter = config.optics.backscatter;
  context.marine_snow = config.optics.marine_snow;
  context.T_B_C = toSe3(config.calibration.T_B_C);
  context.T_C_U = toSe3(config.calibration.T_C_U);
  summary.scene_triangles = scene.triangles.size();
  writePly(partial / "truth" / "scene.ply", PlyMesh{scene.vertices, {}, scene.triangles, {}});
  scene_stage.stop();

  // ---- trajectory ----------------------------------------------------------
  auto motion_stage = timings.stage("trajectory");
  const double above_scene = caster.bounds().min().z() - 1.0;
  auto seabed_z = [&](double north, double east) {
    const RayHit hit = caster.intersect(
        Ray{Eigen::Vector3d(north, east, above_scene), Eigen::Vector3d(0.0, 0.0, 1.0)});
    return hit.hit() ? above_scene + hit.distance : config.scene.seabed_depth_m;
  };
  VehicleMotionConfig vehicle = motion_config;
  vehicle.start_time_s = config.start_time_s;
  vehicle.seed = noiseSeed(config.seed, kMotion, 0);
  const VehicleTrajectory trajectory(vehicle, seabed_z);
  const SE3d T_B_C = toSe3(config.calibration.T_B_C);
  const SE3d T_C_U = toSe3(config.calibration.T_C_U);
  const double d = config.calibration.time_offset_s;
  const double margin = 0.5 + std::abs(d);
  const double record_begin = trajectory.startTime() + margin;
  const double record_end = trajectory.endTime() - margin;
  if (!(record_end > record_begin + 0.5)) {
    throw std::invalid_argument("simulate: the trajectory lasts " +
                                std::to_string(trajectory.endTime() - trajectory.startTime()) +
                                " s, too short to record anything; increase motion.length_m");
  }
  summary.survey_seconds = record_end - record_begin;
  motion_stage.stop();

  // ---- RGB -----------------------------------------------------------------
  auto rgb_stage = timings.stage("rgb frames");
  std::optional<RgbVideoConfig> rgb_video;  // set when the frames are one video file
  {
    const RgbRenderer renderer(context, config.rgb, noiseSeed(config.seed, kRgb, 0));
    const PinholeRadtanCamera rgb_camera(config.rgb.camera);
    const double exposure_s = config.rgb.exposure_s;
    // The camera and body poses over frame k's exposure (rgb_motion_blur.h).
    auto exposurePoses = [&](double t) {
      std::vector<RgbRenderer::Pose> poses;
      int subframes = 1;
      if (exposure_s > 0.0) {
        const SE3d T_W_C_begin = trajectory.T_W_B(t - 0.5 * exposure_s) * T_B_C;
        const SE3d T_W_C_end = trajectory.T_W_B(t + 0.5 * exposure_s) * T_B_C;
        subframes = motionBlurSubframes(imageMotionPx(rgb_camera, caster, T_W_C_begin, T_W_C_end));
      }
      for (double t_sub : subframeTimes(t, exposure_s, subframes)) {
        const SE3d T_W_B = trajectory.T_W_B(t_sub);
        poses.push_back({T_W_B, T_W_B * T_B_C});
      }
      return poses;
    };
    std::vector<double> times;
    for (std::int64_t k = 0;; ++k) {
      const double t = record_begin + k / config.rgb.rate_hz;
      if (t > record_end) break;
      times.push_back(t);
    }
    RgbAutoGain auto_gain(config.rgb.auto_gain, config.rgb.rate_hz);
    std::vector<double> gains_db(times.size(), 0.0);
    std::vector<FrameRow> frames(times.size());
    std::vector<TruthPose> poses(times.size());
    Progress progress("rgb frames", std::int64_t(times.size()), "frames", log);
    constexpr int kBatch = 4;  // image files encoded in parallel
    std::vector<cv::Mat> images(kBatch);
    RgbFrameWriter writer(partial / "rgb", config.rgb.encoding,
                          cv::Size(config.rgb.camera.width, config.rgb.camera.height),
                          config.rgb.rate_hz);
    for (std::size_t k0 = 0; k0 < times.size(); k0 += kBatch) {
      const int count = int(std::min<std::size_t>(kBatch, times.size() - k0));
      for (int i = 0; i < count; ++i) {
        const std::size_t k = k0 + i;
        const SE3d T_W_B = trajectory.T_W_B(times[k]);
        const SE3d T_W_C = T_W_B * T_B_C;
        gains_db[k] = auto_gain.gainDb();
        // A dropout is not rendered: each frame's noise has its own seed, so
        // the other frames do not change.
        if (inBlackout(config.rgb.blackouts, times[k] - trajectory.startTime())) {
          images[i] = cv::Mat::zeros(config.rgb.camera.height, config.rgb.camera.width, CV_8UC3);
        } else {
          images[i] = renderer.render(exposurePoses(times[k]), auto_gain.gain(), std::int64_t(k));
          if (config.rgb.auto_gain.enabled) {
            const cv::Scalar mean = cv::mean(images[i]);
            auto_gain.meter(std::int64_t(k), (mean[0] + mean[1] + mean[2]) / 3.0);
          }
        }
        frames[k] = FrameRow{writer.frameFile(std::int64_t(k)), times[k], 0};
        poses[k] = TruthPose{times[k], T_W_C};
      }
      writer.write(std::int64_t(k0), std::vector<cv::Mat>(images.begin(), images.begin() + count));
      progress.advance(count);
    }
    progress.finish();
    summary.rgb_bytes = writer.finish();
    summary.rgb_format = rgbFrameFormatName(config.rgb.encoding.format);
    summary.rgb_rate_hz = config.rgb.rate_hz;
    if (writer.isVideo()) {
      rgb_video = RgbVideoConfig{RgbFrameWriter::videoPath(), times.front(), config.rgb.rate_hz};
    } else {
      writeFramesCsv(partial / "rgb" / "frames.csv", frames);
    }
    writeTruthPoses(partial / "truth" / "rgb_poses.csv", poses);
    if (config.rgb.auto_gain.enabled) {
      writeRgbGainTruth(partial / "truth" / "rgb_gain.csv", times, gains_db);
    }
    summary.rgb_frames = int(frames.size());
    summary.rgb_width = config.rgb.camera.width;
    summary.rgb_height = config.rgb.camera.height;
  }
  rgb_stage.stop();

  // ---- UHI -----------------------------------------------------------------
  auto uhi_stage = timings.stage("uhi lines");
  const std::vector<double> wavelengths = uhiBandCentres(config.uhi);
  const UhiRenderer uhi(context, config.uhi, wavelengths, noiseSeed(config.seed, kUhi, 0));
  // The contract's radiometry: K(lambda) of the lamps, from the renderer's
  // own model (survey.yaml's `lights` names it).
  writeLampResponseCsv(partial / "uhi" / "lamp_response.csv", uhi.lampResponseDn());
  const double sample_spacing_m = motion_config.altitude_m / config.uhi.camera.f;
  const WorldExtent scene_extent = turnedSceneExtent(scene_config);
  SwathFootprint footprint(scene_extent.north_min_m, scene_extent.north_max_m,
                           scene_extent.east_min_m, scene_extent.east_max_m,
                           config.truth.ortho_pixel_m,
                           int(config.truth.ortho_pixel_m / sample_spacing_m / 2.0));
  {
    // The first line is recorded a fraction of a line period after the first
    // frame: the two cameras are not triggered together.
    const double first_line = record_begin + 0.37 / config.uhi.rate_hz;
    std::vector<double> line_times;
    for (std::int64_t j = 0;; ++j) {
      const double t = first_line + j / config.uhi.rate_hz;
      if (t > record_end) break;
      line_times.push_back(t);
    }
    EnviWriter cube(partial / "uhi" / "cube.hdr", uhiCubeHeader(config, wavelengths));
    std::vector<TruthLinePose> poses(line_times.size());
    UhiLineImage line;
    Progress progress("uhi lines", std::int64_t(line_times.size()), "lines", log);
    for (std::size_t j = 0; j < line_times.size(); ++j) {
      const double t_true = line_times[j] + d;
      const SE3d T_W_B = trajectory.T_W_B(t_true);
      const SE3d T_W_U = T_W_B * T_B_C * T_C_U;
      uhi.render(T_W_B, T_W_U, std::int64_t(j), line);
      cube.writeLine(line.dn);
      footprint.addLine(line.centre_hits_W);
      poses[j] = TruthLinePose{static_cast<long long>(j), t_true, T_W_U};
      progress.advance();
    }
    cube.finish();
    progress.finish();
    writeLinesCsv(partial / "uhi" / "lines.csv", line_times);
    writeTruthLinePoses(partial / "truth" / "uhi_poses.csv", poses);
    summary.uhi_lines = int(line_times.size());
    summary.uhi_samples = config.uhi.camera.samples;
    summary.uhi_bands = config.uhi.bands;
  }
  uhi_stage.stop();

  // ---- INS, survey.yaml, calibration ----------------------------------------
  auto ins_stage = timings.stage("ins and calibration");
  {
    const LocalNedFrame w_frame(config.origin);
    InsNoiseConfig noise = config.ins;
    noise.seed = noiseSeed(config.seed, kIns, 0);
    const InsTable ins =
        synthesizeIns(trajectory, noise, w_frame, trajectory.startTime(), trajectory.endTime());
    writeInsCsv(partial / "nav" / "ins.csv", ins);
    summary.ins_fixes = int(ins.fixes.size());
    SurveyConfig survey = surveyConfig(config, summary.survey_seconds, rgb_video);
    survey.lights = lamps.lightsInCamera(config.calibration.T_B_C);
    writeSurveyConfig(partial / "survey.yaml", survey);

    TruthCalibration calibration;
    calibration.T_C_U = toConfig(T_C_U);
    calibration.time_offset_s = d;
    calibration.T_B_C = config.calibration.T_B_C;
    calibration.rgb_camera = config.rgb.camera;
    calibration.uhi_camera = config.uhi.camera;
    for (double nm : wavelengths) {
      calibration.water_attenuation_per_m.push_back(
          waterAttenuationPerM(nm, config.optics.turbidity));
    }
    // The contract's additive backscatter(lambda), at nadir at the nominal
    // altitude (uhi_renderer.h); absent (zeros) without backscatter.
    calibration.backscatter_dn = uhi.nominalBackscatterDn();
    writeTruthCalibration(partial / "truth" / "calibration.yaml", calibration);
  }
  ins_stage.stop();

  // ---- truth reflectance -----------------------------------------------------
  auto ortho_stage = timings.stage("truth reflectance");
  const ReflectanceOrthoSummary ortho =
      writeReflectanceOrtho(partial / "truth" / "reflectance.hdr", footprint, context, wavelengths, log);
  summary.reflectance_rows = ortho.rows;
  summary.reflectance_cols = ortho.cols;
  summary.reflectance_valid_pixels = ortho.valid_pixels;
  ortho_stage.stop();

  std::filesystem::remove_all(target);
  std::filesystem::rename(partial, target);
  summary.stage_seconds = timings.seconds();
  summary.peak_memory_mb = peakResidentMemoryMb();
  return summary;
}

}  // namespace hsmap
