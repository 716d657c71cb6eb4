#include "core/survey/pose_tables.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

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

SE3d randomPose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::Quaterniond q(uniform(rng), uniform(rng), uniform(rng), uniform(rng));
  q.normalize();
  return SE3d(q, Eigen::Vector3d(30.0 * uniform(rng), 30.0 * uniform(rng), 10.0 + uniform(rng)));
}

std::vector<TimedPose> randomTimedPoses(std::size_t count) {
  std::mt19937_64 rng(21);
  std::vector<TimedPose> poses;
  for (std::size_t i = 0; i < count; ++i) {
    poses.push_back({1700000000.123456 + i / 25.0 + 1e-7 * (i % 3), randomPose(rng)});
  }
  return poses;
}

class PoseTablesTest : public ::testing::Test {
 protected:
  TempFolder folder_{"pose-tables"};
};

TEST_F(PoseTablesTest, TimedTableRoundTripsBitExactlyAndRewritesTheSameBytes) {
  const std::vector<TimedPose> poses = randomTimedPoses(40);
  const auto path = folder_ / "frames.csv";
  writeTimedPoseTable(path, poses);
  const std::vector<TimedPose> read = readTimedPoseTable(path);
  ASSERT_EQ(read.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read[i].t, poses[i].t);
    EXPECT_EQ(read[i].T.t, poses[i].T.t);
    EXPECT_EQ(read[i].T.q.coeffs(), poses[i].T.q.coeffs());
  }
  writeTimedPoseTable(folder_ / "again.csv", read);
  EXPECT_EQ(TempFolder::read(folder_ / "again.csv"), TempFolder::read(path));
  EXPECT_FALSE(std::filesystem::exists(folder_ / "frames.csv.partial"));
}

TEST_F(PoseTablesTest, LineTableRoundTripsBitExactly) {
  std::mt19937_64 rng(22);
  std::vector<LinePose> poses;
  for (long long i = 0; i < 30; ++i) poses.push_back({i, 12.015 + i * 0.01, randomPose(rng)});
  const auto path = folder_ / "uhi_lines.csv";
  writeLinePoseTable(path, poses);
  EXPECT_EQ(TempFolder::read(path).substr(0, 25), "line,t,x,y,z,qw,qx,qy,qz\n");
  const std::vector<LinePose> read = readLinePoseTable(path);
  ASSERT_EQ(read.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(read[i].line, poses[i].line);
    EXPECT_EQ(read[i].t, poses[i].t);
    EXPECT_EQ(read[i].T.t, poses[i].T.t);
    EXPECT_EQ(read[i].T.q.coeffs(), poses[i].T.q.coeffs());
  }
}

TEST_F(PoseTablesTest, TheFilesLookAsDocumented) {
  const SE3d T(Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5), Eigen::Vector3d(1.5, -2.0, 0.1));
  writeTimedPoseTable(folder_ / "frames.csv", {{36000.04, T}, {36000.08, SE3d()}});
  EXPECT_EQ(TempFolder::read(folder_ / "frames.csv"),
            "t,x,y,z,qw,qx,qy,qz\n"
            "36000.04,1.5,-2,0.1,0.5,0.5,-0.5,0.5\n"
            "36000.08,0,0,0,1,0,0,0\n");
  writeLinePoseTable(folder_ / "lines.csv", {{0, 1.25, T}});
  EXPECT_EQ(TempFolder::read(folder_ / "lines.csv"),
            "line,t,x,y,z,qw,qx,qy,qz\n"
            "0,1.25,1.5,-2,0.1,0.5,0.5,-0.5,0.5\n");
  // TUM: "t tx ty tz qx qy qz qw", quaternion w last, no header.
  writeTumTrajectory(folder_ / "frames.tum", {{36000.04, T}, {36000.08, SE3d()}});
  EXPECT_EQ(TempFolder::read(folder_ / "frames.tum"),
            "36000.04 1.5 -2 0.1 0.5 -0.5 0.5 0.5\n"
            "36000.08 0 0 0 0 0 0 1\n");
}

TEST_F(PoseTablesTest, ReadersNameTheFileLineAndProblem) {
  const auto quaternion = folder_ / "q.csv";
  writeText(quaternion, "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n1,0,0,0,1,0,0,0.5\n");
  expectInputError([&] { readTimedPoseTable(quaternion); }, quaternion,
                   "line 3: columns qw,qx,qy,qz: expected a unit quaternion (norm within 1e-06 "
                   "of 1), got norm 1.118033988749895");
  const auto order = folder_ / "order.csv";
  writeText(order, "t,x,y,z,qw,qx,qy,qz\n2,0,0,0,1,0,0,0\n1.5,0,0,0,1,0,0,0\n");
  expectInputError([&] { readTimedPoseTable(order); }, order,
                   "line 3: time 't' = 1.5 is earlier than the previous row's 2: rows must be in "
                   "time order");
  const auto lines = folder_ / "lines.csv";
  writeText(lines, "line,t,x,y,z,qw,qx,qy,qz\n0,1,0,0,0,1,0,0,0\n2,2,0,0,0,1,0,0,0\n");
  expectInputError([&] { readLinePoseTable(lines); }, lines,
                   "line 3: column 'line': expected scan line 1 (one row per scan line, counting "
                   "from 0 in order), got 2");
  const auto header = folder_ / "header.csv";
  writeText(header, "t x y z qx qy qz qw\n0 0 0 0 0 0 0 1\n");
  expectInputError([&] { readTimedPoseTable(header); }, header,
                   "line 1: expected the header 't,x,y,z,qw,qx,qy,qz', got 't x y z qx qy qz qw'");
}

TEST_F(PoseTablesTest, WritersRefuseWhatTheReadersWouldRefuse) {
  const auto path = folder_ / "out.csv";
  std::vector<TimedPose> poses = randomTimedPoses(3);
  poses[1].T.q = Eigen::Quaterniond(0.0, 0.0, 0.0, 1.5);
  EXPECT_EQ(invalidArgumentMessage([&] { writeTimedPoseTable(path, poses); }),
            "writeTimedPoseTable: pose at time 1700000000.163456: expected a unit quaternion "
            "(norm within 1e-06 of 1), got norm 1.5");
  EXPECT_EQ(invalidArgumentMessage([&] { writeTumTrajectory(path, poses); }),
            "writeTumTrajectory: pose at time 1700000000.163456: expected a unit quaternion "
            "(norm within 1e-06 of 1), got norm 1.5");
  poses = randomTimedPoses(3);
  poses[2].t = poses[0].t;
  EXPECT_EQ(invalidArgumentMessage([&] { writeTimedPoseTable(path, poses, "georef"); }),
            "georef: times must be strictly increasing, got 1700000000.123456 after "
            "1700000000.163456");
  EXPECT_EQ(invalidArgumentMessage([&] { writeLinePoseTable(path, {{1, 0.0, SE3d()}}); }),
            "writeLinePoseTable: expected scan line 0 at position 0, got 1");
  EXPECT_EQ(invalidArgumentMessage([&] { writeLinePoseTable(path, {}); }),
            "writeLinePoseTable: expected at least one scan line");
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace hsmap
