#pragma once
// A survey with a hand-made ground truth and a results folder, for the tests
// of `hsmap evaluate`. The survey is a copy of the built-in sample (75 frames
// at 25 Hz and 90 scan lines at 30 Hz from t = 36000 s; it loads in well
// under a second) whose truth/ and nav/ins.csv are replaced by a known
// analytic motion, so that every metric has a value the test can work out:
//
//   body B:  north = 0.5 tau, east = 0.4 sin(0.9 tau), down = 20 + 0.05 tau,
//            roll = 2 sin(1.1 tau), pitch = 1.5 cos(0.6 tau),
//            heading = 10 + 5 sin(0.7 tau) degrees,   tau = t - 36000 s
//   T_W_C = T_W_B * T_B_C (survey.yaml's camera_in_body), T_W_U = T_W_C(t + d) * T_C_U
//   INS fixes exactly on the body at every 5th frame time (5 Hz), with attitude,
//   plus one fix before and one after the frames' time span.
//
// truth/scene.ply is a flat seabed at down = kSeabedDown (flatSeabed), and
// truth/reflectance.* a 200 x 200 raster of 1 cm pixels over north
// [0.5, 2.5] m, east [-1, 1] m, NaN in its 20 westernmost and 20 easternmost
// columns: the footprint is north [0.5, 2.5] x east [-0.8, 0.8]
// (kFootprint*). Only the mesh metrics read them.
// writeRun() writes a results folder from given trajectories and calibration,
// writeRunMesh() its map/mesh.ply.

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "core/geometry/local_ned_frame.h"
#include "core/geometry/so3.h"
#include "core/io/envi_writer.h"
#include "core/io/ply_io.h"
#include "core/survey/csv_table.h"
#include "core/survey/pose_tables.h"
#include "core/survey/run_calibration.h"
#include "core/survey/run_record.h"
#include "core/survey/survey_config.h"
#include "core/survey/truth_files.h"
#include "tests/support/pristine_sample.h"
#include "tests/support/temp_folder.h"

namespace hsmap::testing {

constexpr double kStartTime = 36000.0;
constexpr double kTrueTimeOffset = 0.015;  // d

inline SE3d trueBodyPose(double t) {
  const double tau = t - kStartTime;
  const Eigen::Vector3d p_W_B(0.5 * tau, 0.4 * std::sin(0.9 * tau), 20.0 + 0.05 * tau);
  const Eigen::Quaterniond q_W_B = quaternionFromRollPitchHeadingDeg(
      2.0 * std::sin(1.1 * tau), 1.5 * std::cos(0.6 * tau), 10.0 + 5.0 * std::sin(0.7 * tau));
  return SE3d(q_W_B, p_W_B);
}

// The true surface and the true ortho-image's footprint (see above).
constexpr double kSeabedDown = 22.0;
constexpr double kPixel = 0.01;
constexpr int kReflectanceRows = 200, kReflectanceCols = 200, kNanColumns = 20;
constexpr double kReflectanceNorthMax = 2.5, kReflectanceEastMin = -1.0;
constexpr double kFootprintNorthMin = 0.5, kFootprintNorthMax = 2.5;
constexpr double kFootprintEastMin = -0.8, kFootprintEastMax = 0.8;

// A flat surface at `down` over [north_min, north_max] x [east_min, east_max]
// in square cells of `cell` metres, two triangles each.
inline PlyMesh flatSeabed(double north_min, double north_max, double east_min, double east_max,
                          double cell, double down) {
  const int rows = static_cast<int>(std::lround((north_max - north_min) / cell));
  const int cols = static_cast<int>(std::lround((east_max - east_min) / cell));
  PlyMesh mesh;
  for (int i = 0; i <= rows; ++i) {
    for (int j = 0; j <= cols; ++j) {
      mesh.vertices.emplace_back(north_min + i * cell, east_min + j * cell, down);
    }
  }
  const auto index = [cols](int i, int j) { return i * (cols + 1) + j; };
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      mesh.triangles.emplace_back(index(i, j), index(i + 1, j), index(i + 1, j + 1));
      mesh.triangles.emplace_back(index(i, j), index(i + 1, j + 1), index(i, j + 1));
    }
  }
  return mesh;
}

// The fixture's true surface: wider than the footprint, in 0.25 m cells.
inline PlyMesh trueSeabed() { return flatSeabed(-1.0, 3.0, -1.5, 1.5, 0.25, kSeabedDown); }

// An ENVI float32 raster in local W (map info Arbitrary, upper-left corner
// at (north_max, east_min)), 0.5 in every band where valid(row, col), NaN elsewhere.
template <typename Valid>
void writeLocalRaster(const std::filesystem::path& hdr, int rows, int cols, int bands,
                      double north_max, double east_min, double pixel, Valid valid) {
  EnviHeader header;
  header.samples = cols;
  header.lines = rows;
  header.bands = bands;
  header.data_type = EnviDataType::float32;
  header.interleave = EnviInterleave::bil;
  EnviMapInfo map;
  map.projection = "Arbitrary";
  map.easting = east_min;
  map.northing = north_max;
  map.pixel_size_x = map.pixel_size_y = pixel;
  map.units = "Meters";
  header.map_info = map;
  EnviWriter writer(hdr, header);
  Eigen::MatrixXf line(bands, cols);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      line.col(c).setConstant(valid(r, c) ? 0.5f : std::numeric_limits<float>::quiet_NaN());
    }
    writer.writeLine(line);
  }
  writer.finish();
}

inline RigidTransformConfig trueExtrinsic() {
  RigidTransformConfig T_C_U;
  T_C_U.rotation = Eigen::Quaterniond(0.999, 0.01, -0.02, 0.03).normalized();
  T_C_U.translation_m = Eigen::Vector3d(0.1, 0.01, -0.02);
  return T_C_U;
}

class EvaluationFixture {
 public:
  EvaluationFixture() {
    copyFolder(pristineSample(), survey_);
    config_ = readSurveyConfig(survey_ / "survey.yaml");
    const SE3d T_B_C(config_.ins.T_B_C.rotation, config_.ins.T_B_C.translation_m);
    const RigidTransformConfig extrinsic = trueExtrinsic();
    const SE3d T_C_U(extrinsic.rotation, extrinsic.translation_m);

    for (const FrameRow& frame : readFramesCsv(survey_ / "rgb/frames.csv")) {
      frames_true_.push_back({frame.t, trueBodyPose(frame.t) * T_B_C});
    }
    const std::vector<double> line_times = readLinesCsv(survey_ / "uhi/lines.csv");
    for (std::size_t k = 0; k < line_times.size(); ++k) {
      const double t = line_times[k] + kTrueTimeOffset;
      lines_true_.push_back({static_cast<long long>(k), t, trueBodyPose(t) * T_B_C * T_C_U});
    }
    calibration_true_.T_C_U = extrinsic;
    calibration_true_.time_offset_s = kTrueTimeOffset;
    calibration_true_.T_B_C = config_.ins.T_B_C;
    calibration_true_.rgb_camera = config_.rgb.camera;
    calibration_true_.uhi_camera = config_.uhi.camera;
    calibration_true_.water_attenuation_per_m = std::vector<double>(16, 0.1);
    writeTruth();
    writeIns(1.0);
  }

  const std::filesystem::path& survey() const { return survey_; }
  std::filesystem::path truth() const { return survey_ / "truth"; }
  const std::filesystem::path& run() const { return run_; }
  const SurveyConfig& config() const { return config_; }
  const std::vector<TimedPose>& framesTrue() const { return frames_true_; }
  const std::vector<LinePose>& linesTrue() const { return lines_true_; }
  const TruthCalibration& calibrationTrue() const { return calibration_true_; }

  // The truth files (rgb_poses.csv, uhi_poses.csv, calibration.yaml, scene.ply, reflectance.*).
  void writeTruth() const {
    std::filesystem::create_directories(truth());
    std::vector<TruthPose> frames;
    for (const TimedPose& pose : frames_true_) frames.push_back({pose.t, pose.T});
    writeTruthPoses(truth() / "rgb_poses.csv", frames);
    std::vector<TruthLinePose> lines;
    for (const LinePose& pose : lines_true_) lines.push_back({pose.line, pose.t, pose.T});
    writeTruthLinePoses(truth() / "uhi_poses.csv", lines);
    writeTruthCalibration(truth() / "calibration.yaml", calibration_true_);
    writePly(truth() / "scene.ply", trueSeabed());
    writeLocalRaster(truth() / "reflectance.hdr", kReflectanceRows, kReflectanceCols, 4,
                     kReflectanceNorthMax, kReflectanceEastMin, kPixel, [](int, int col) {
                       return col >= kNanColumns && col < kReflectanceCols - kNanColumns;
                     });
  }

  // nav/ins.csv: the true body at every 5th frame time and just outside the
  // frames' span; with `scale`, the body of the camera trajectory multiplied
  // by `scale` about W's origin, the lever arm in metres (1: exact).
  void writeIns(double scale) const {
    const LocalNedFrame ned(*config_.origin);
    std::vector<double> times = {frames_true_.front().t - 0.2};
    for (std::size_t i = 0; i < frames_true_.size(); i += 5) times.push_back(frames_true_[i].t);
    times.push_back(frames_true_.back().t + 0.2);
    InsTable table;
    table.has_attitude = true;
    for (double t : times) {
      const SE3d T_W_B = trueBodyPose(t);
      const SE3d T_W_C = T_W_B * SE3d(config_.ins.T_B_C.rotation, config_.ins.T_B_C.translation_m);
      const GeodeticPoint point = ned.toGeodetic(scale * T_W_C.t + (T_W_B.t - T_W_C.t));
      const Eigen::Vector3d rph = rollPitchHeadingDegFromQuaternion(T_W_B.q);
      InsFix fix;
      fix.t = t;
      fix.lat_deg = point.lat_deg;
      fix.lon_deg = point.lon_deg;
      fix.depth_m = point.depth_m;
      fix.roll_deg = rph[0];
      fix.pitch_deg = rph[1];
      fix.heading_deg = rph[2];
      table.fixes.push_back(fix);
    }
    writeInsCsv(survey_ / "nav/ins.csv", table);
  }

  static RunRecord record() {
    RunRecord record;
    record.program_version = "0.1.0";
    record.variant = "sequential";
    record.started_utc = "2026-12-01T23:30:00Z";
    record.options = {{"until", "georef"}};
    record.stages = {{"frontend", 12.5, 240.1}, {"georef", 3.25, 300.0}};
    record.total_time_s = 15.75;
    record.peak_rss_mb = 300.5;
    return record;
  }

  RunCalibration calibrationEqualToTruth() const {
    RunCalibration calibration;
    calibration.variant = "sequential";
    calibration.T_C_U = calibration_true_.T_C_U;
    calibration.time_offset_s = calibration_true_.time_offset_s;
    return calibration;
  }

  // A results folder with these contents (the truth's by default).
  void writeRun(const std::vector<TimedPose>& frames, const std::vector<LinePose>& lines,
                const RunCalibration& calibration) const {
    std::filesystem::create_directories(run_ / "trajectory");
    RunRecord run_record = record();
    run_record.survey = std::filesystem::absolute(survey_);
    writeRunRecord(run_ / "run.yaml", run_record);
    writeTimedPoseTable(run_ / "trajectory/frames.csv", frames);
    writeLinePoseTable(run_ / "trajectory/uhi_lines.csv", lines);
    writeRunCalibration(run_ / "calibration.yaml", calibration);
  }
  // RUN/map/mesh.ply (in the run's W).
  void writeRunMesh(const PlyMesh& mesh) const {
    std::filesystem::create_directories(run_ / "map");
    writePly(run_ / "map/mesh.ply", mesh);
  }
  void writeRunEqualToTruth() const {
    writeRun(frames_true_, lines_true_, calibrationEqualToTruth());
  }

 private:
  TempFolder temp_{"evaluate"};
  std::filesystem::path survey_ = temp_ / "survey";
  std::filesystem::path run_ = temp_ / "run";
  SurveyConfig config_;
  std::vector<TimedPose> frames_true_;
  std::vector<LinePose> lines_true_;
  TruthCalibration calibration_true_;
};

}  // namespace hsmap::testing
