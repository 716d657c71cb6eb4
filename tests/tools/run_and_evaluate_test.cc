// `hsmap run` (both variants) and `hsmap evaluate` on the simulated `tiny`
// survey, through the real binary: every file the data contract lists for
// these stages is written and reads back under its rules, the rows match the
// survey, and the scores say what the variants are (sequential's shape to
// millimetres, its absolute error below planar's). Then a fix that jumped
// metres is found and reported, and a failed run leaves no product.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/io/envi_reader.h"
#include "core/io/ply_io.h"
#include "core/survey/csv_table.h"
#include "core/survey/pose_tables.h"
#include "core/survey/run_calibration.h"
#include "core/survey/run_record.h"
#include "core/survey/survey.h"
#include "pipelines/evaluate/evaluation_metrics.h"
#include "tests/support/run_hsmap.h"
#include "tests/support/temp_folder.h"
#include "tests/tools/simulated_tiny_survey.h"

namespace hsmap {
namespace {

using testing::quoted;
using testing::readText;
using testing::RunResult;
using testing::runHsmap;
using testing::TempFolder;

namespace fs = std::filesystem;

const fs::path& tinySurvey() { return testing::simulatedTinySurvey(); }

// A number of metrics.json by key; NaN when the key is missing, and the
// text "null" gives -1 (the metrics checked here are never negative).
double metric(const std::string& json, const std::string& key) {
  const std::regex pattern("\"" + key + "\"\\s*:\\s*(null|[-0-9.eE+]+)");
  std::smatch match;
  if (!std::regex_search(json, match, pattern)) return std::nan("");
  return match[1] == "null" ? -1.0 : std::stod(match[1]);
}

class RunAndEvaluate : public ::testing::Test {
 protected:
  TempFolder temp_{"run-evaluate"};

  RunResult run(const std::string& variant, const fs::path& out, const fs::path& survey = tinySurvey(),
                const std::string& extra = "") {
    return runHsmap(temp_, "run " + quoted(survey.string()) + " --out " + quoted(out.string()) +
                               " --variant " + variant + extra);
  }

  // Every file of the contract these stages write, read back strictly.
  void expectContractFiles(const fs::path& out, const std::string& variant,
                           const std::string& last_stage = "products") {
    const Survey survey = loadSurvey(tinySurvey());
    const auto frames = readTimedPoseTable(out / "trajectory/frames.csv");
    ASSERT_EQ(frames.size(), survey.rgb.times().size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
      EXPECT_EQ(frames[i].t, survey.rgb.times()[i]) << "frame " << i;  // copied exactly
    }
    const auto lines = readLinePoseTable(out / "trajectory/uhi_lines.csv");
    ASSERT_EQ(lines.size(), survey.line_times.size());
    for (std::size_t i = 0; i < lines.size(); ++i) {
      EXPECT_EQ(lines[i].line, static_cast<long long>(i));
      EXPECT_DOUBLE_EQ(lines[i].t, survey.line_times[i] + survey.config.uhi.time_offset_s);
    }
    EXPECT_EQ(testing::countLines(out / "trajectory/frames.tum"), static_cast<long long>(frames.size()));
    const RunCalibration calibration = readRunCalibration(out / "calibration.yaml");
    EXPECT_EQ(calibration.variant, variant);
    EXPECT_TRUE(calibration.T_C_U.rotation.isApprox(survey.config.uhi.T_C_U.rotation));
    EXPECT_FALSE(calibration.sigma_rotation_deg.has_value());  // not estimated: null
    const RunRecord record = readRunRecord(out / "run.yaml");
    EXPECT_EQ(record.variant, variant);
    EXPECT_EQ(fs::canonical(record.survey), fs::canonical(tinySurvey()));
    ASSERT_FALSE(record.stages.empty());
    EXPECT_EQ(record.stages.back().name, last_stage);
    // The products of every variant (docs/PRODUCTS.md).
    for (const char* product : {"hyperspectral/ortho.hdr", "hyperspectral/ortho.raw", "hyperspectral/ortho.tif",
                                "hyperspectral/ortho_rgb.png", "hyperspectral/ancillary.hdr",
                                "hyperspectral/points.ply", "map/rgb_ortho.png", "map/rgb_ortho.tif"}) {
      EXPECT_TRUE(fs::is_regular_file(out / product)) << product;
    }
    EXPECT_FALSE(fs::exists(out / "hyperspectral.partial"));
    EXPECT_FALSE(fs::exists(out / "georef.partial"));
  }
};

TEST_F(RunAndEvaluate, SequentialAndPlanarWriteTheContractAndScoreAsTheyShould) {
  const fs::path sequential = temp_ / "sequential";
  const RunResult seq = run("sequential", sequential);
  ASSERT_EQ(seq.exit_status, 0) << seq.err << seq.out;
  for (const char* expected : {"georef (sequential)", "Levenberg", "INS fixes left out: none",
                               "stage times and peak memory", "run.yaml written"}) {
    EXPECT_NE(seq.out.find(expected), std::string::npos) << "missing '" << expected << "' in\n" << seq.out;
  }
  expectContractFiles(sequential, "sequential");
  EXPECT_GT(readPly(sequential / "map/sparse.ply").vertices.size(), 100u);
  const PlyMesh mesh = readPly(sequential / "map/mesh.ply");  // dense, the default
  ASSERT_EQ(mesh.colors.size(), mesh.vertices.size());  // RGB from the keyframes
  EXPECT_NE(seq.out.find("dense points: "), std::string::npos) << seq.out;
  EXPECT_NE(seq.out.find("surface (dense): "), std::string::npos) << seq.out;
  EXPECT_EQ(readRunRecord(sequential / "run.yaml").options.at("surface"), "dense");

  // The reference paper's surface from the landmarks alone, beside it: the
  // dense one has several times the triangles.
  const fs::path sparse = temp_ / "sparse";
  const RunResult spa = run("sequential", sparse, tinySurvey(), " --surface sparse");
  ASSERT_EQ(spa.exit_status, 0) << spa.err << spa.out;
  EXPECT_NE(spa.out.find("vertex colours from "), std::string::npos) << spa.out;
  const PlyMesh sparse_mesh = readPly(sparse / "map/mesh.ply");
  EXPECT_GT(sparse_mesh.triangles.size(), 100u);
  EXPECT_GT(mesh.triangles.size(), 3 * sparse_mesh.triangles.size());

  const fs::path planar = temp_ / "planar";
  const RunResult pla = run("planar", planar);
  ASSERT_EQ(pla.exit_status, 0) << pla.err << pla.out;
  expectContractFiles(planar, "planar");
  EXPECT_FALSE(fs::exists(planar / "map/sparse.ply"));  // no vision, no landmarks
  EXPECT_FALSE(fs::exists(planar / "frontend"));
  // Its surface is the flat seabed at the estimated depth, under the track.
  EXPECT_EQ(readRunRecord(planar / "run.yaml").options.at("surface"), "flat");
  EXPECT_NE(pla.out.find("surface (flat): seabed at z = "), std::string::npos) << pla.out;
  const PlyMesh plane = readPly(planar / "map/mesh.ply");
  ASSERT_FALSE(plane.vertices.empty());
  for (const auto& v : plane.vertices) ASSERT_EQ(v.z(), plane.vertices.front().z());
  const auto frames_planar = readTimedPoseTable(planar / "trajectory/frames.csv");
  EXPECT_GT(plane.vertices.front().z(), frames_planar.front().T.t.z() + 0.5);  // below the camera

  const fs::path truth = tinySurvey() / "truth";
  std::string json[2], printed[2];
  for (int v = 0; v < 2; ++v) {
    const fs::path out = v == 0 ? sequential : planar;
    const RunResult evaluate =
        runHsmap(temp_, "evaluate " + quoted(out.string()) + " --truth " + quoted(truth.string()));
    ASSERT_EQ(evaluate.exit_status, 0) << evaluate.err << evaluate.out;
    json[v] = readText(out / "metrics.json");
    printed[v] = evaluate.out;
    for (const char* key : {"rgb_ate_m", "rgb_ate_aligned_m", "rgb_scale_error", "uhi_position_rmse_m",
                            "uhi_rotation_rmse_deg", "extrinsic_rotation_error_deg",
                            "extrinsic_translation_error_m", "time_offset_error_s", "mesh_accuracy_m",
                            "mesh_completeness", "ortho_mean_shift_m", "ortho_registration_rmse_m",
                            "ortho_scale_error", "ortho_sam_deg", "ortho_coverage", "ortho_pixel_error_m",
                            "ortho_pixel_error_abs_m", "peak_rss_mb"}) {
      EXPECT_FALSE(std::isnan(metric(json[v], key))) << key << " missing from\n" << json[v];
    }
    EXPECT_NE(json[v].find("\"timings_s\""), std::string::npos) << json[v];
    // Both ortho-images cover most of the true footprint, with every band
    // of the cube and its wavelengths, on a map grid.
    EXPECT_GT(metric(json[v], "ortho_coverage"), 0.7) << json[v];
    const Survey survey = loadSurvey(tinySurvey());
    const EnviReader ortho(out / "hyperspectral/ortho.hdr");
    EXPECT_EQ(ortho.bands(), survey.cube->bands());
    EXPECT_EQ(ortho.header().wavelength, survey.wavelengths_nm);
    EXPECT_TRUE(ortho.header().map_info.has_value());
    const EnviReader ancillary(out / "hyperspectral/ancillary.hdr");
    EXPECT_EQ(ancillary.samples(), ortho.samples());
    EXPECT_EQ(ancillary.lines(), ortho.lines());
    EXPECT_NE(evaluate.out.find("rgb_ate_m"), std::string::npos) << evaluate.out;
  }
  // The shape of the trajectory to millimetres (vision); placed by the INS
  // better than the INS alone places it.
  EXPECT_LT(metric(json[0], "rgb_ate_aligned_m"), 0.01) << json[0];
  EXPECT_LT(metric(json[0], "rgb_ate_m"), metric(json[1], "rgb_ate_m")) << json[0] << json[1];
  EXPECT_GT(metric(json[1], "rgb_ate_aligned_m"), metric(json[0], "rgb_ate_aligned_m"));
  // The dense surface is measured; planar has none. On tiny the frames'
  // positions (a 0.7 m track, a few millimetres of cross-track spread)
  // leave the roll about the track undetermined, so an alignment of the
  // positions alone may turn the seabed by degrees; the contract's view
  // Sim(3) (each frame's centre and its view point on the seabed) fixes it,
  // and holds the mesh to millimetres (2.2 mm measured) and nearly all of
  // the true surface.
  EXPECT_LT(metric(json[0], "mesh_accuracy_m"), 0.005) << json[0];
  EXPECT_GT(metric(json[0], "mesh_completeness"), 0.9) << json[0];
  // The ortho-image's distortion, matching-free: vision's map is several
  // times less distorted than the INS alone's (4.7 and 20.9 mm measured).
  EXPECT_LT(metric(json[0], "ortho_pixel_error_m"), 0.008) << json[0];
  EXPECT_GT(metric(json[1], "ortho_pixel_error_m"), 2.0 * metric(json[0], "ortho_pixel_error_m")) << json[1];
  EXPECT_LT(metric(json[0], "alignment_cross_track_spread_m"), kWeakRollCrossTrackSpreadM) << json[0];
  EXPECT_NE(printed[0].find("positions alone leave the roll about the track weakly determined"),
            std::string::npos)
      << printed[0];
  EXPECT_LT(metric(json[0], "mesh_accuracy_attitude_aligned_m"), 0.008) << json[0];
  EXPECT_GT(metric(json[0], "mesh_completeness_attitude_aligned"), 0.85) << json[0];
  // planar's flat seabed is measured like any mesh: it misses the relief.
  EXPECT_GT(metric(json[1], "mesh_accuracy_m"), metric(json[0], "mesh_accuracy_attitude_aligned_m")) << json[1];
}

TEST_F(RunAndEvaluate, AFixThatJumpedMetresIsLeftOutAndReportedByItsLine) {
  const fs::path survey = temp_ / "jumped";
  testing::copyFolder(tinySurvey(), survey);
  // Fix 12 (line 14 of ins.csv) moved 5 m north.
  InsTable ins = readInsCsv(survey / "nav/ins.csv");
  ins.fixes[12].lat_deg += 5.0 / 111120.0;
  writeInsCsv(survey / "nav/ins.csv", ins);
  const RunResult result = run("sequential", temp_ / "out", survey);
  ASSERT_EQ(result.exit_status, 0) << result.err << result.out;
  EXPECT_NE(result.out.find("INS fixes left out (1):"), std::string::npos) << result.out;
  EXPECT_TRUE(std::regex_search(result.out, std::regex("ins.csv line 14 \\(t = [0-9.]+ s\\): (4\\.[5-9]|5\\.[0-4])[0-9]* m "
                                                       "off the track, found by the alignment")))
      << result.out;
}

TEST_F(RunAndEvaluate, ATrackingLossIsBridgedByTheInsAndSaysSo) {
  // Frames 20-33 black: the front-end loses tracking and starts a second
  // segment; georef bridges the gap with the INS, anchored on both sides.
  const fs::path survey = temp_ / "blanked";
  testing::copyFolder(tinySurvey(), survey);
  const Survey loaded = loadSurvey(survey);
  const cv::Mat black = cv::Mat::zeros(loaded.config.rgb.camera.height, loaded.config.rgb.camera.width, CV_8UC3);
  for (int i = 20; i <= 33; ++i) ASSERT_TRUE(cv::imwrite(loaded.rgb.framePath(i).string(), black));
  const fs::path out = temp_ / "out";
  const RunResult result = run("sequential", out, survey);
  ASSERT_EQ(result.exit_status, 0) << result.err << result.out;
  EXPECT_NE(result.out.find("2 segments"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("frames: 44 from vision, 14 bridged by the INS across tracking gaps"),
            std::string::npos)
      << result.out;
  // pose_sources.csv names exactly those frames.
  const std::string sources = readText(out / "trajectory/pose_sources.csv");
  for (int i = 0; i < 58; ++i) {
    const bool blank = i >= 20 && i <= 33;
    const std::regex row("\\nframe," + std::to_string(i) + ",[^,]+," + (blank ? "ins_bridged" : "vision") + "\\n");
    EXPECT_TRUE(std::regex_search(sources, row)) << "frame " << i;
  }
  // Every frame is still there, and the bridged ones are where the INS puts them.
  const auto frames = readTimedPoseTable(out / "trajectory/frames.csv");
  ASSERT_EQ(frames.size(), loaded.rgb.times().size());
  const RunResult evaluate = runHsmap(temp_, "evaluate " + quoted(out.string()) + " --truth " +
                                                 quoted((survey / "truth").string()));
  ASSERT_EQ(evaluate.exit_status, 0) << evaluate.err;
  EXPECT_LT(metric(readText(out / "metrics.json"), "rgb_ate_m"), 0.2);
}

TEST_F(RunAndEvaluate, JointWithTooFewTiePointsKeepsTheSequentialResultAndSaysWhy) {
  // tiny's UHI has 240 samples over a few seconds: far fewer than the 20
  // confident tie points the joint problem needs.
  const fs::path joint = temp_ / "joint";
  const RunResult result = run("joint", joint);
  ASSERT_EQ(result.exit_status, 0) << result.err << result.out;
  EXPECT_NE(result.out.find("warning: joint: round 1 not solved; the sequential result"), std::string::npos)
      << result.out;
  expectContractFiles(joint, "joint");
  const RunCalibration calibration = readRunCalibration(joint / "calibration.yaml");
  // The joint stage's two, then the radiometry stage's (tiny has lights),
  // each naming its stage.
  ASSERT_GE(calibration.warnings.size(), 2u);
  for (std::size_t i = 2; i < calibration.warnings.size(); ++i) {
    EXPECT_EQ(calibration.warnings[i].rfind("radiometry: ", 0), 0u) << calibration.warnings[i];
  }
  EXPECT_EQ(calibration.warnings[0],
            "T_C_U and time_offset_s are survey.yaml's guesses: the joint problem could not be solved");
  EXPECT_NE(calibration.warnings[1].find("cross-modal tie points (need 20)"), std::string::npos)
      << calibration.warnings[1];
  EXPECT_EQ(readRunRecord(joint / "run.yaml").options.at("joint_rounds"), "3");
  EXPECT_EQ(readRunRecord(joint / "run.yaml").options.at("joint_tie_points"), "strip");

  const RunResult evaluate = runHsmap(
      temp_, "evaluate " + quoted(joint.string()) + " --truth " + quoted((tinySurvey() / "truth").string()));
  ASSERT_EQ(evaluate.exit_status, 0) << evaluate.err << evaluate.out;
  const std::string json = readText(joint / "metrics.json");
  EXPECT_GT(metric(json, "extrinsic_rotation_error_deg"), 0.5);  // the survey's 2 deg guess, kept
  EXPECT_GT(metric(json, "time_offset_error_s"), 0.005);         // and its 15 ms off d

  // `--from joint` starts from the run's own sequential start (RUN/georef/),
  // whatever the joint stage published: a calibration.yaml damaged in place
  // is not read, and the stage gives the same calibration again.
  const std::string first_calibration = readText(joint / "calibration.yaml");
  RunCalibration solved = calibration;
  solved.time_offset_sigma_s = 0.002;
  writeRunCalibration(joint / "calibration.yaml", solved);
  const RunResult again = run("joint", joint, tinySurvey(), " --from joint");
  ASSERT_EQ(again.exit_status, 0) << again.err << again.out;
  EXPECT_NE(again.out.find("and the sequential start from " + (joint / "georef").string()), std::string::npos)
      << again.out;
  EXPECT_EQ(readText(joint / "calibration.yaml"), first_calibration);
}

TEST_F(RunAndEvaluate, StackedWritesTheLinesSideBySideAndScoresNothing) {
  const fs::path stacked = temp_ / "stacked";
  const RunResult result = run("stacked", stacked);
  ASSERT_EQ(result.exit_status, 0) << result.err << result.out;
  const Survey survey = loadSurvey(tinySurvey());
  const EnviReader ortho(stacked / "hyperspectral/ortho.hdr");
  EXPECT_EQ(ortho.lines(), survey.cube->lines());
  EXPECT_EQ(ortho.samples(), survey.cube->samples());
  EXPECT_FALSE(ortho.header().map_info.has_value());
  EXPECT_TRUE(fs::is_regular_file(stacked / "hyperspectral/ortho_rgb.png"));
  EXPECT_FALSE(fs::exists(stacked / "trajectory"));
  EXPECT_EQ(readRunRecord(stacked / "run.yaml").stages.back().name, "products");

  const RunResult evaluate = runHsmap(
      temp_, "evaluate " + quoted(stacked.string()) + " --truth " + quoted((tinySurvey() / "truth").string()));
  ASSERT_EQ(evaluate.exit_status, 0) << evaluate.err << evaluate.out;
  const std::string json = readText(stacked / "metrics.json");
  for (const char* key : {"rgb_ate_m", "uhi_position_rmse_m", "mesh_accuracy_m", "ortho_registration_rmse_m",
                          "ortho_coverage"}) {
    EXPECT_EQ(metric(json, key), -1.0) << key << "\n" << json;
  }
  EXPECT_NE(evaluate.out.find("the stacked variant poses nothing"), std::string::npos) << evaluate.out;
}

TEST_F(RunAndEvaluate, AFailedStageLeavesNoProductAndNoRunYaml) {
  // The INS logged nothing while the video ran: no fix within vision.
  const fs::path survey = temp_ / "ins-gap";
  testing::copyFolder(tinySurvey(), survey);
  const Survey loaded = loadSurvey(tinySurvey());
  InsTable ins = readInsCsv(survey / "nav/ins.csv");
  std::erase_if(ins.fixes, [&](const InsFix& fix) {
    return fix.t >= loaded.rgb.times().front() && fix.t <= loaded.rgb.times().back();
  });
  writeInsCsv(survey / "nav/ins.csv", ins);
  const fs::path out = temp_ / "out";
  const RunResult result = run("sequential", out, survey);
  EXPECT_EQ(result.exit_status, 1) << result.out;
  EXPECT_NE(result.err.find("error: stage georef failed: cannot geo-reference"), std::string::npos) << result.err;
  EXPECT_TRUE(fs::exists(out / "frontend/frames.csv"));  // the stage before it completed
  for (const char* product :
       {"run.yaml", "trajectory", "calibration.yaml", "map", "georef", "georef.partial", "stages/georef.yaml"}) {
    EXPECT_FALSE(fs::exists(out / product)) << product;
  }
}

}  // namespace
}  // namespace hsmap
