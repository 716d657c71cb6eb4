#include "core/survey/truth_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/util/input_error.h"
#include "tests/support/expect_input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::expectInputError;
using testing::TempFolder;
using testing::writeText;

template <typename Call>
std::string invalidArgumentMessage(Call call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

// Random poses with awkward digits: times like a Unix clock, quaternions
// normalised by Eigen (unit to double precision), sub-millimetre translations.
SE3d randomPose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::Quaterniond q(uniform(rng), uniform(rng), uniform(rng), uniform(rng));
  q.normalize();
  return SE3d(q, Eigen::Vector3d(30.0 * uniform(rng), 30.0 * uniform(rng), 10.0 + uniform(rng)));
}

std::vector<TruthPose> randomPoses(std::size_t count) {
  std::mt19937_64 rng(11);
  std::vector<TruthPose> poses;
  for (std::size_t i = 0; i < count; ++i) {
    poses.push_back({1700000000.123456 + i / 25.0 + 1e-7 * (i % 3), randomPose(rng)});
  }
  return poses;
}

std::vector<TruthLinePose> randomLinePoses(std::size_t count) {
  std::mt19937_64 rng(12);
  std::vector<TruthLinePose> poses;
  for (std::size_t i = 0; i < count; ++i) {
    poses.push_back({static_cast<long long>(i), 12.015 + i * 0.01, randomPose(rng)});
  }
  return poses;
}

TruthCalibration exampleCalibration() {
  TruthCalibration calibration;
  calibration.T_C_U.rotation = Eigen::Quaterniond(0.9, 0.1, -0.2, 0.05).normalized();
  calibration.T_C_U.translation_m = Eigen::Vector3d(0.1, -0.013, 0.0021);
  calibration.time_offset_s = 0.015;
  calibration.T_B_C.rotation = Eigen::Quaterniond(0.5, -0.5, 0.5, -0.5);
  calibration.T_B_C.translation_m = Eigen::Vector3d(0.5, 0.0, 0.3);
  calibration.rgb_camera = {960, 540, 800.5, 801.25, 480.1, 269.9, {0.1, -0.05, 1e-3, 2e-3, 0.01}};
  calibration.uhi_camera = {1920, 1500.0, 959.5, {0.01, 0.002}};
  calibration.water_attenuation_per_m = {0.05, 0.0412345678901, 0.3, 1.0 / 3.0};
  return calibration;
}

void expectSamePose(const SE3d& a, const SE3d& b) {
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.q.coeffs(), b.q.coeffs());
}

class TruthFilesTest : public ::testing::Test {
 protected:
  TempFolder folder_{"truth"};
  std::filesystem::path file(const std::string& name, const std::string& text) {
    const auto path = folder_ / name;
    writeText(path, text);
    return path;
  }
};

// ---- round trips -------------------------------------------------------------

TEST_F(TruthFilesTest, PosesRoundTripBitExactly) {
  const std::vector<TruthPose> poses = randomPoses(50);
  const auto path = folder_ / "rgb_poses.csv";
  writeTruthPoses(path, poses);
  EXPECT_EQ(TempFolder::read(path).substr(0, 20), "t,x,y,z,qw,qx,qy,qz\n");
  const std::vector<TruthPose> read = readTruthPoses(path);
  ASSERT_EQ(read.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read[i].t, poses[i].t);
    expectSamePose(read[i].T_W_X, poses[i].T_W_X);
  }
  // Writing what was read gives the same bytes.
  const auto again = folder_ / "again.csv";
  writeTruthPoses(again, read);
  EXPECT_EQ(TempFolder::read(again), TempFolder::read(path));
  EXPECT_FALSE(std::filesystem::exists(folder_ / "rgb_poses.csv.partial"));
}

TEST_F(TruthFilesTest, LinePosesRoundTripBitExactly) {
  const std::vector<TruthLinePose> poses = randomLinePoses(40);
  const auto path = folder_ / "uhi_poses.csv";
  writeTruthLinePoses(path, poses);
  EXPECT_EQ(TempFolder::read(path).substr(0, 25), "line,t,x,y,z,qw,qx,qy,qz\n");
  const std::vector<TruthLinePose> read = readTruthLinePoses(path);
  ASSERT_EQ(read.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read[i].line, static_cast<long long>(i));
    EXPECT_EQ(read[i].t, poses[i].t);
    expectSamePose(read[i].T_W_U, poses[i].T_W_U);
  }
}

TEST_F(TruthFilesTest, CalibrationRoundTripsBitExactly) {
  const TruthCalibration calibration = exampleCalibration();
  const auto path = folder_ / "calibration.yaml";
  writeTruthCalibration(path, calibration);
  const TruthCalibration read = readTruthCalibration(path);
  EXPECT_EQ(read.T_C_U.rotation.coeffs(), calibration.T_C_U.rotation.coeffs());
  EXPECT_EQ(read.T_C_U.translation_m, calibration.T_C_U.translation_m);
  EXPECT_EQ(read.time_offset_s, calibration.time_offset_s);
  EXPECT_EQ(read.T_B_C.rotation.coeffs(), calibration.T_B_C.rotation.coeffs());
  EXPECT_EQ(read.T_B_C.translation_m, calibration.T_B_C.translation_m);
  EXPECT_EQ(read.rgb_camera.width, 960);
  EXPECT_EQ(read.rgb_camera.height, 540);
  EXPECT_EQ(read.rgb_camera.fx, 800.5);
  EXPECT_EQ(read.rgb_camera.fy, 801.25);
  EXPECT_EQ(read.rgb_camera.cx, 480.1);
  EXPECT_EQ(read.rgb_camera.cy, 269.9);
  EXPECT_EQ(read.rgb_camera.distortion, calibration.rgb_camera.distortion);
  EXPECT_EQ(read.uhi_camera.samples, 1920);
  EXPECT_EQ(read.uhi_camera.f, 1500.0);
  EXPECT_EQ(read.uhi_camera.cx, 959.5);
  EXPECT_EQ(read.uhi_camera.distortion, calibration.uhi_camera.distortion);
  EXPECT_EQ(read.water_attenuation_per_m, calibration.water_attenuation_per_m);
  const auto again = folder_ / "again.yaml";
  writeTruthCalibration(again, read);
  EXPECT_EQ(TempFolder::read(again), TempFolder::read(path));
}

TEST_F(TruthFilesTest, ReadsTheDocumentedCalibrationExample) {
  const auto path = file("calibration.yaml",
                         "format: hsmap-truth/1\n"
                         "T_C_U: {rotation_wxyz: [1, 0, 0, 0], translation_m: [0.1, 0, 0]}\n"
                         "time_offset_s: 0.015\n"
                         "T_B_C: {rotation_wxyz: [1, 0, 0, 0], translation_m: [0.5, 0, 0.3]}\n"
                         "rgb_camera: {model: pinhole-radtan, width: 960, height: 540,\n"
                         "             fx: 800, fy: 800, cx: 480, cy: 270}\n"
                         "uhi_camera: {model: pushbroom, samples: 1920, f: 1500, cx: 960}\n"
                         "water_attenuation_per_m: [0.1, 0.05, 0]\n");
  const TruthCalibration read = readTruthCalibration(path);
  EXPECT_EQ(read.time_offset_s, 0.015);
  EXPECT_EQ(read.T_B_C.translation_m, Eigen::Vector3d(0.5, 0, 0.3));
  EXPECT_EQ(read.rgb_camera.distortion, (std::array<double, 5>{0, 0, 0, 0, 0}));
  EXPECT_EQ(read.water_attenuation_per_m, (std::vector<double>{0.1, 0.05, 0.0}));
}

TEST_F(TruthFilesTest, NearlyUnitQuaternionIsNormalisedUnitOneKeptExactly) {
  const auto path = file("rgb_poses.csv",
                         "t,x,y,z,qw,qx,qy,qz\n"
                         "0,1,2,3,1.0000005,0,0,0\n"
                         "1,1,2,3,0.6,0.8,0,0\n");
  const std::vector<TruthPose> poses = readTruthPoses(path);
  EXPECT_EQ(poses[0].T_W_X.q.w(), 1.0);
  EXPECT_EQ(poses[1].T_W_X.q.w(), 0.6);  // 0.36 + 0.64 rounds to 1 within 1e-15
  EXPECT_EQ(poses[1].T_W_X.q.x(), 0.8);
  EXPECT_EQ(poses[1].T_W_X.t, Eigen::Vector3d(1, 2, 3));
}

// ---- malformed CSV -----------------------------------------------------------

TEST_F(TruthFilesTest, WrongHeader) {
  const auto path = file("rgb_poses.csv", "t,x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,0,1\n");
  expectInputError([&] { readTruthPoses(path); }, path,
                   "line 1: expected the header 't,x,y,z,qw,qx,qy,qz', got 't,x,y,z,qx,qy,qz,qw'");
  const auto lines = file("uhi_poses.csv", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n");
  expectInputError([&] { readTruthLinePoses(lines); }, lines,
                   "line 1: expected the header 'line,t,x,y,z,qw,qx,qy,qz', got "
                   "'t,x,y,z,qw,qx,qy,qz'");
}

TEST_F(TruthFilesTest, NonUnitQuaternion) {
  const auto path = file("rgb_poses.csv",
                         "t,x,y,z,qw,qx,qy,qz\n"
                         "0,0,0,0,1,0,0,0\n"
                         "1,0,0,0,1,0,0,0.5\n");
  expectInputError([&] { readTruthPoses(path); }, path,
                   "line 3: columns qw,qx,qy,qz: expected a unit quaternion (norm within 1e-06 "
                   "of 1), got norm 1.118033988749895");
  const auto lines = file("uhi_poses.csv",
                          "line,t,x,y,z,qw,qx,qy,qz\n"
                          "0,0,0,0,0,0.999998,0,0,0\n");
  expectInputError([&] { readTruthLinePoses(lines); }, lines,
                   "line 2: columns qw,qx,qy,qz: expected a unit quaternion (norm within 1e-06 "
                   "of 1), got norm 0.999998");
}

TEST_F(TruthFilesTest, DecreasingOrRepeatedTime) {
  const auto path = file("rgb_poses.csv",
                         "t,x,y,z,qw,qx,qy,qz\n"
                         "2,0,0,0,1,0,0,0\n"
                         "1.5,0,0,0,1,0,0,0\n");
  expectInputError([&] { readTruthPoses(path); }, path,
                   "line 3: time 't' = 1.5 is earlier than the previous row's 2: rows must be in "
                   "time order");
  const auto lines = file("uhi_poses.csv",
                          "line,t,x,y,z,qw,qx,qy,qz\n"
                          "0,2,0,0,0,1,0,0,0\n"
                          "1,2,0,0,0,1,0,0,0\n");
  expectInputError([&] { readTruthLinePoses(lines); }, lines,
                   "line 3: time 't' = 2 equals the previous row's: duplicated time stamp");
}

TEST_F(TruthFilesTest, LinesMustCountFromZero) {
  const auto path = file("uhi_poses.csv",
                         "line,t,x,y,z,qw,qx,qy,qz\n"
                         "0,1,0,0,0,1,0,0,0\n"
                         "2,2,0,0,0,1,0,0,0\n");
  expectInputError([&] { readTruthLinePoses(path); }, path,
                   "line 3: column 'line': expected scan line 1 (one row per scan line, counting "
                   "from 0 in order), got 2");
}

TEST_F(TruthFilesTest, BadCellsAndCounts) {
  const auto nan = file("rgb_poses.csv", "t,x,y,z,qw,qx,qy,qz\n0,nan,0,0,1,0,0,0\n");
  expectInputError([&] { readTruthPoses(nan); }, nan,
                   "line 2: column 'x': expected a finite number, got 'nan'");
  const auto short_row = file("short.csv", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0\n");
  expectInputError([&] { readTruthPoses(short_row); }, short_row,
                   "line 2: expected 8 columns (t,x,y,z,qw,qx,qy,qz), got 7");
  const auto empty = file("empty.csv", "t,x,y,z,qw,qx,qy,qz\n");
  expectInputError([&] { readTruthPoses(empty); }, empty,
                   "line 2: no data rows; expected at least one row after the header "
                   "'t,x,y,z,qw,qx,qy,qz'");
}

// ---- malformed calibration.yaml ---------------------------------------------

class TruthCalibrationErrorTest : public TruthFilesTest {
 protected:
  // The example calibration as written, with `from` replaced by `to` (exactly once).
  std::filesystem::path variant(const std::string& from, const std::string& to) {
    const auto path = folder_ / "calibration.yaml";
    writeTruthCalibration(path, exampleCalibration());
    testing::replaceInFile(path, from, to);
    return path;
  }
};

TEST_F(TruthCalibrationErrorTest, TheWrittenFileLooksAsDocumented) {
  writeTruthCalibration(folder_ / "calibration.yaml", exampleCalibration());
  EXPECT_EQ(testing::readText(folder_ / "calibration.yaml"),
            "# hsmap ground-truth calibration (format: see docs/SURVEY_FORMAT.md)\n"
            "format: hsmap-truth/1\n"
            "T_C_U: {rotation_wxyz: [0.9690874237046979, 0.1076763804116331, -0.2153527608232662, "
            "0.05383819020581655], translation_m: [0.1, -0.013, 0.0021]}\n"
            "time_offset_s: 0.015\n"
            "T_B_C: {rotation_wxyz: [0.5, -0.5, 0.5, -0.5], translation_m: [0.5, 0, 0.3]}\n"
            "rgb_camera: {model: pinhole-radtan, width: 960, height: 540, fx: 800.5, fy: 801.25, "
            "cx: 480.1, cy: 269.9, distortion: [0.1, -0.05, 0.001, 0.002, 0.01]}\n"
            "uhi_camera: {model: pushbroom, samples: 1920, f: 1500, cx: 959.5, distortion: "
            "[0.01, 0.002]}\n"
            "water_attenuation_per_m: [0.05, 0.0412345678901, 0.3, 0.3333333333333333]\n");
}

TEST_F(TruthCalibrationErrorTest, WrongFormatString) {
  const auto path = variant("format: hsmap-truth/1", "format: hsmap-survey/1");
  expectInputError([&] { readTruthCalibration(path); }, path,
                   "line 2, key format: unsupported format 'hsmap-survey/1'; expected "
                   "'hsmap-truth/1'");
}

TEST_F(TruthCalibrationErrorTest, MissingKey) {
  const auto path = variant("time_offset_s: 0.015\n", "");
  expectInputError([&] { readTruthCalibration(path); }, path,
                   "line 2, key time_offset_s: missing required key");
  const auto no_attenuation =
      variant("water_attenuation_per_m: [0.05, 0.0412345678901, 0.3, 0.3333333333333333]\n", "");
  expectInputError([&] { readTruthCalibration(no_attenuation); }, no_attenuation,
                   "line 2, key water_attenuation_per_m: missing required key");
  const auto no_rotation =
      variant("T_B_C: {rotation_wxyz: [0.5, -0.5, 0.5, -0.5], ", "T_B_C: {");
  expectInputError([&] { readTruthCalibration(no_rotation); }, no_rotation,
                   "line 5, key T_B_C.rotation_wxyz: missing required key");
}

TEST_F(TruthCalibrationErrorTest, UnknownKey) {
  const auto path = variant("time_offset_s:", "time_ofset_s:");
  expectInputError([&] { readTruthCalibration(path); }, path,
                   "line 4, key time_ofset_s: unknown key; expected one of: format, T_C_U, "
                   "time_offset_s, T_B_C, rgb_camera, uhi_camera, water_attenuation_per_m, backscatter_dn");
}

TEST_F(TruthCalibrationErrorTest, AttenuationMustBeANonEmptyListOfNonNegativeNumbers) {
  const std::string list = "[0.05, 0.0412345678901, 0.3, 0.3333333333333333]";
  expectInputError([&] { readTruthCalibration(variant(list, "[]")); }, folder_ / "calibration.yaml",
                   "line 8, key water_attenuation_per_m: expected a non-empty list of numbers >= 0 "
                   "(one per UHI band), got an empty list");
  expectInputError([&] { readTruthCalibration(variant(list, "0.05")); },
                   folder_ / "calibration.yaml",
                   "line 8, key water_attenuation_per_m: expected a non-empty list of numbers >= 0 "
                   "(one per UHI band), got '0.05'");
  expectInputError([&] { readTruthCalibration(variant(list, "[0.05, -0.1]")); },
                   folder_ / "calibration.yaml",
                   "line 8, key water_attenuation_per_m[1]: expected a number >= 0, got -0.1");
  expectInputError([&] { readTruthCalibration(variant(list, "[0.05, abc]")); },
                   folder_ / "calibration.yaml",
                   "line 8, key water_attenuation_per_m[1]: expected a number, got 'abc'");
  expectInputError([&] { readTruthCalibration(variant(list, "[0.05, [1]]")); },
                   folder_ / "calibration.yaml",
                   "line 8, key water_attenuation_per_m[1]: expected a number, got a list");
}

// The contract's optional backscatter per band: read and written when
// given, one per band as the attenuation.
TEST_F(TruthCalibrationErrorTest, BackscatterIsOptionalAndOnePerBand) {
  const std::string list = "water_attenuation_per_m: [0.05, 0.0412345678901, 0.3, 0.3333333333333333]\n";
  const auto path = variant(list, list + "backscatter_dn: [12.5, 0, 3, 4]\n");
  const TruthCalibration read = readTruthCalibration(path);
  EXPECT_EQ(read.backscatter_dn, (std::vector<double>{12.5, 0.0, 3.0, 4.0}));
  EXPECT_TRUE(readTruthCalibration(variant("format: hsmap-truth/1", "format: hsmap-truth/1")).backscatter_dn.empty());
  const auto again = folder_ / "again.yaml";
  writeTruthCalibration(again, read);
  EXPECT_EQ(readTruthCalibration(again).backscatter_dn, read.backscatter_dn);
  expectInputError([&] { readTruthCalibration(variant(list, list + "backscatter_dn: [1, 2]\n")); },
                   folder_ / "calibration.yaml",
                   "line 9, key backscatter_dn: expected 4 numbers (one per UHI band, as water_attenuation_per_m), "
                   "got 2");
  expectInputError([&] { readTruthCalibration(variant(list, list + "backscatter_dn: [1, 2, -3, 4]\n")); },
                   folder_ / "calibration.yaml", "line 9, key backscatter_dn[2]: expected a number >= 0, got -3");
}

TEST_F(TruthCalibrationErrorTest, BadCameraAndRotation) {
  const auto model = variant("model: pushbroom", "model: linescan");
  expectInputError([&] { readTruthCalibration(model); }, model,
                   "line 7, key uhi_camera.model: unsupported camera model 'linescan'; expected "
                   "'pushbroom'");
  const auto rotation = variant(
      "[0.9690874237046979, 0.1076763804116331, -0.2153527608232662, 0.05383819020581655]",
      "[0, 0, 2, 0]");
  expectInputError([&] { readTruthCalibration(rotation); }, rotation,
                   "line 3, key T_C_U.rotation_wxyz: expected a unit quaternion [w, x, y, z] "
                   "(norm within 0.001 of 1), got norm 2");
  const auto empty = file("empty.yaml", "");
  expectInputError([&] { readTruthCalibration(empty); }, empty,
                   "line 1: empty file; expected a YAML map starting with 'format: hsmap-truth/1'");
}

// ---- writers refuse what the readers would refuse ----------------------------

TEST_F(TruthFilesTest, WritersRejectDataTheirReadersWouldRefuse) {
  const auto path = folder_ / "out.csv";
  std::vector<TruthPose> poses = randomPoses(3);
  poses[2].t = poses[1].t;
  EXPECT_EQ(invalidArgumentMessage([&] { writeTruthPoses(path, poses); }),
            "writeTruthPoses: times must be strictly increasing, got 1700000000.163456 after "
            "1700000000.163456");
  poses = randomPoses(3);
  poses[1].T_W_X.q = Eigen::Quaterniond(0.0, 0.0, 0.0, 1.5);
  EXPECT_EQ(invalidArgumentMessage([&] { writeTruthPoses(path, poses); }),
            "writeTruthPoses: pose at time 1700000000.163456: expected a unit quaternion (norm "
            "within 1e-06 of 1), got norm 1.5");
  poses = randomPoses(3);
  poses[0].T_W_X.t.x() = NAN;
  EXPECT_EQ(invalidArgumentMessage([&] { writeTruthPoses(path, poses); }),
            "writeTruthPoses: non-finite value at time 1700000000.123456");
  EXPECT_EQ(invalidArgumentMessage([&] { writeTruthPoses(path, {}); }),
            "writeTruthPoses: expected at least one pose");

  std::vector<TruthLinePose> lines = randomLinePoses(3);
  lines[2].line = 5;
  EXPECT_EQ(invalidArgumentMessage([&] { writeTruthLinePoses(path, lines); }),
            "writeTruthLinePoses: expected scan line 2 at position 2, got 5");
  EXPECT_FALSE(std::filesystem::exists(path));

  TruthCalibration calibration = exampleCalibration();
  calibration.water_attenuation_per_m.clear();
  EXPECT_EQ(invalidArgumentMessage(
                [&] { writeTruthCalibration(folder_ / "calibration.yaml", calibration); }),
            "writeTruthCalibration: invalid calibration: " +
                (folder_ / "calibration.yaml").string() +
                ":line 8, key water_attenuation_per_m: expected a non-empty list of numbers >= 0 "
                "(one per UHI band), got an empty list");
  calibration = exampleCalibration();
  calibration.rgb_camera.fx = -1.0;
  EXPECT_THROW(writeTruthCalibration(folder_ / "calibration.yaml", calibration),
               std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(folder_ / "calibration.yaml"));
}

}  // namespace
}  // namespace hsmap
