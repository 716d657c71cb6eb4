#include "pipelines/frontend/frontend_outputs.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

FrontendResult sampleResult() {
  FrontendResult result;
  VisualMap& map = result.map;
  map.addKeyframe(0, 36000.04, 0, SE3d(expSO3(Eigen::Vector3d(0.1, -0.2, 0.3)), Eigen::Vector3d(0.1, 1.0 / 3.0, -2.5)));
  map.addKeyframe(7, 36000.32, 0, SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1e-7, 0.0, 4.0)));
  map.addKeyframe(20, 36000.84, 1, SE3d(expSO3(Eigen::Vector3d(0.0, 0.01, 0.0)), Eigen::Vector3d(2.0, 0.5, 0.25)));
  for (int l = 0; l < 4; ++l) map.addLandmark(0, Eigen::Vector3d(0.1 * l, -0.3, 1.0 + 1.0 / (l + 3.0)));
  map.addObservation(0, 0, {10.25, 20.5});
  map.addObservation(1, 0, {12.125, 19.0});
  map.addObservation(0, 1, {100.0, 200.0});
  map.addObservation(1, 1, {101.0, 202.0});
  map.addObservation(2, 1, {99.5, 201.0});
  map.addObservation(0, 2, {5.0, 6.0});
  map.addObservation(2, 3, {7.0, 8.0});
  map.addObservation(1, 3, {7.5, 8.5});
  map.removeLandmark(2);  // a removed landmark leaves a gap in the ids
  for (int i = 0; i < 25; ++i) {
    FrameRecord f;
    f.index = i;
    f.t = 36000.0 + 0.04 * (i + 1);
    f.posed = i < 10 || i >= 20;
    f.segment = i < 10 ? 0 : (i >= 20 ? 1 : -1);
    f.status = f.posed ? FrameStatus::tracking : FrameStatus::no_texture;
    if (f.posed) f.T_F_C = SE3d(expSO3(Eigen::Vector3d(0.01 * i, 0.0, 0.0)), Eigen::Vector3d(0.1 * i, 0.0, 0.0));
    f.keyframe = i == 0 || i == 7 || i == 20;
    f.keyframe_id = i == 0 ? 0 : (i == 7 ? 1 : (i == 20 ? 2 : -1));
    f.tracked = 200 + i;
    f.inliers = 150 + i;
    f.new_corners = i % 3;
    for (int s = 0; s < kFrontendStepCount; ++s) f.ms[std::size_t(s)] = 0.125 * (s + 1) + i;
    result.frames.push_back(f);
  }
  // Posed frames 0-9 and 20-24; landmarks 0, 1 and 3 (2 was removed). Pixels
  // that a float holds but a short decimal does not (1/3, 0.1).
  result.frame_observations = {{0, 0, 10.25f, 20.5f},           {0, 1, 100.0f, 200.0f},
                               {3, 0, 1.0f / 3.0f, 639.999f},   {3, 3, 0.1f, 1e-5f},
                               {7, 1, 101.0f, 202.0f},          {7, 3, 7.5f, 8.5f},
                               {21, 1, 99.25f, 201.123456789f}};
  result.losses.push_back({10, 19, "no texture: dark (mean 0.0 DN, contrast 0.0 DN)"});
  SegmentRecord s0;
  s0.id = 0;
  s0.first_frame = 0;
  s0.last_frame = 9;
  s0.keyframes = 2;
  s0.reference = s0.linked = true;
  s0.note = "reference segment";
  SegmentRecord s1 = s0;
  s1.id = 1;
  s1.first_frame = 20;
  s1.last_frame = 24;
  s1.keyframes = 1;
  s1.reference = false;
  s1.S_F_S = Sim3(0.75, expSO3(Eigen::Vector3d(0.0, 0.0, 0.5)), Eigen::Vector3d(1.0, 2.0, 3.0));
  s1.ins_rms_m = 0.0625;
  s1.note = "linked into F through the INS, scale 0.75";
  result.segments = {s0, s1};
  return result;
}

TEST(FrontendOutputs, RoundTripKeepsMapFramesLossesAndSegments) {
  testing::TempFolder run;
  const FrontendResult written = sampleResult();
  writeFrontendOutputs(run.path(), written);
  EXPECT_FALSE(std::filesystem::exists(run / "frontend.partial"));
  const FrontendResult read = readFrontendOutputs(run.path());

  ASSERT_EQ(read.map.keyframes().size(), written.map.keyframes().size());
  for (std::size_t k = 0; k < written.map.keyframes().size(); ++k) {
    const Keyframe& a = written.map.keyframes()[k];
    const Keyframe& b = read.map.keyframes()[k];
    EXPECT_EQ(a.frame_index, b.frame_index);
    EXPECT_EQ(a.t, b.t);
    EXPECT_EQ(a.segment, b.segment);
    EXPECT_EQ(a.T_F_C.t, b.T_F_C.t);
    EXPECT_EQ(a.T_F_C.q.coeffs(), b.T_F_C.q.coeffs());
    ASSERT_EQ(a.observations.size(), b.observations.size());
    for (std::size_t i = 0; i < a.observations.size(); ++i) {
      EXPECT_EQ(a.observations[i].landmark_id, b.observations[i].landmark_id);
      EXPECT_EQ(a.observations[i].pixel, b.observations[i].pixel);
    }
  }
  ASSERT_EQ(read.map.landmarks().size(), written.map.landmarks().size());
  for (std::size_t l = 0; l < written.map.landmarks().size(); ++l) {
    const Landmark& a = written.map.landmarks()[l];
    const Landmark& b = read.map.landmarks()[l];
    EXPECT_EQ(a.valid, b.valid) << l;
    if (!a.valid) continue;
    EXPECT_EQ(a.p_F, b.p_F);
    std::vector<int> ka = a.keyframe_ids, kb = b.keyframe_ids;
    std::sort(ka.begin(), ka.end());
    std::sort(kb.begin(), kb.end());
    EXPECT_EQ(ka, kb);
  }
  ASSERT_EQ(read.frames.size(), written.frames.size());
  for (std::size_t i = 0; i < written.frames.size(); ++i) {
    const FrameRecord& a = written.frames[i];
    const FrameRecord& b = read.frames[i];
    EXPECT_EQ(a.index, b.index);
    EXPECT_EQ(a.t, b.t);
    EXPECT_EQ(a.posed, b.posed);
    EXPECT_EQ(a.segment, b.segment);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.keyframe, b.keyframe);
    EXPECT_EQ(a.keyframe_id, b.keyframe_id);
    EXPECT_EQ(a.tracked, b.tracked);
    EXPECT_EQ(a.inliers, b.inliers);
    EXPECT_EQ(a.new_corners, b.new_corners);
    EXPECT_EQ(a.ms, b.ms);
    if (a.posed) {
      EXPECT_EQ(a.T_F_C.t, b.T_F_C.t);
      EXPECT_EQ(a.T_F_C.q.coeffs(), b.T_F_C.q.coeffs());
    }
  }
  ASSERT_EQ(read.frame_observations.size(), written.frame_observations.size());
  for (std::size_t i = 0; i < written.frame_observations.size(); ++i) {
    const FrameObservation& a = written.frame_observations[i];
    const FrameObservation& b = read.frame_observations[i];
    EXPECT_EQ(a.frame, b.frame) << i;
    EXPECT_EQ(a.landmark, b.landmark) << i;
    EXPECT_EQ(a.u, b.u) << i;  // bit-identical floats
    EXPECT_EQ(a.v, b.v) << i;
  }
  ASSERT_EQ(read.losses.size(), 1u);
  EXPECT_EQ(read.losses[0].first_frame, 10);
  EXPECT_EQ(read.losses[0].last_frame, 19);
  EXPECT_EQ(read.losses[0].reason, "no texture: dark (mean 0.0 DN; contrast 0.0 DN)");  // commas become ';'
  ASSERT_EQ(read.segments.size(), 2u);
  EXPECT_TRUE(read.segments[0].reference);
  EXPECT_FALSE(read.segments[1].reference);
  EXPECT_TRUE(read.segments[1].linked);
  EXPECT_EQ(read.segments[1].S_F_S.scale(), 0.75);
  EXPECT_LT((read.segments[1].S_F_S.translation() - Eigen::Vector3d(1.0, 2.0, 3.0)).norm(), 1e-15);
  EXPECT_NEAR(read.segments[1].S_F_S.rotation().angularDistance(written.segments[1].S_F_S.rotation()), 0.0, 1e-12);
  EXPECT_EQ(read.segments[1].ins_rms_m, 0.0625);
  EXPECT_EQ(read.segments[1].note, "linked into F through the INS; scale 0.75");
}

TEST(FrontendOutputs, FrameObservationsAreWrittenInShortFloatForm) {
  testing::TempFolder run;
  writeFrontendOutputs(run.path(), sampleResult());
  EXPECT_EQ(testing::readText(run / "frontend" / "frame_observations.csv"),
            "frame,landmark,u,v\n"
            "0,0,10.25,20.5\n"
            "0,1,100,200\n"
            "3,0,0.33333334,639.999\n"
            "3,3,0.1,1e-05\n"
            "7,1,101,202\n"
            "7,3,7.5,8.5\n"
            "21,1,99.25,201.12346\n");
}

TEST(FrontendOutputs, ObservationsOfFrameAreThatFramesRows) {
  const FrontendResult result = sampleResult();
  const auto frame3 = result.observationsOfFrame(3);
  ASSERT_EQ(frame3.size(), 2u);
  EXPECT_EQ(frame3[0].landmark, 0);
  EXPECT_EQ(frame3[1].landmark, 3);
  EXPECT_EQ(result.observationsOfFrame(21).size(), 1u);
  EXPECT_TRUE(result.observationsOfFrame(12).empty());
  EXPECT_TRUE(result.observationsOfFrame(99).empty());
}

TEST(FrontendOutputs, ARunWithoutLossesOrFrameObservationsReadsBack) {
  testing::TempFolder run;
  FrontendResult written = sampleResult();
  written.losses.clear();
  written.frame_observations.clear();
  writeFrontendOutputs(run.path(), written);
  const FrontendResult read = readFrontendOutputs(run.path());
  EXPECT_TRUE(read.losses.empty());
  EXPECT_TRUE(read.frame_observations.empty());
  EXPECT_EQ(read.frames.size(), written.frames.size());
}

TEST(FrontendOutputs, TumFileHoldsThePosedFramesInTumOrder) {
  testing::TempFolder run;
  const FrontendResult written = sampleResult();
  writeFrontendOutputs(run.path(), written);
  std::istringstream tum(testing::readText(run / "frontend" / "frames.tum"));
  std::string line;
  int rows = 0;
  while (std::getline(tum, line)) {
    double t, x, y, z, qx, qy, qz, qw;
    std::istringstream cells(line);
    ASSERT_TRUE(cells >> t >> x >> y >> z >> qx >> qy >> qz >> qw) << line;
    const FrameRecord* frame = nullptr;
    for (const auto& f : written.frames) {
      if (f.t == t) frame = &f;
    }
    ASSERT_NE(frame, nullptr);
    EXPECT_TRUE(frame->posed);
    EXPECT_EQ(x, frame->T_F_C.t.x());
    EXPECT_EQ(qw, frame->T_F_C.q.w());
    EXPECT_EQ(qx, frame->T_F_C.q.x());
    ++rows;
  }
  EXPECT_EQ(rows, written.posedFrameCount());
}

TEST(FrontendOutputs, RewritingReplacesTheFolderWhole) {
  testing::TempFolder run;
  writeFrontendOutputs(run.path(), sampleResult());
  testing::writeText(run / "frontend" / "stale.txt", "old");
  writeFrontendOutputs(run.path(), sampleResult());
  EXPECT_FALSE(std::filesystem::exists(run / "frontend" / "stale.txt"));
}

TEST(FrontendOutputs, ReaderNamesTheFileAndLineOfABadRow) {
  testing::TempFolder run;
  writeFrontendOutputs(run.path(), sampleResult());
  testing::replaceInFile(run / "frontend" / "observations.csv", "1,1,101,202", "1,9,101,202");
  try {
    readFrontendOutputs(run.path());
    FAIL() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("observations.csv:line 5"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("unknown landmark 9"), std::string::npos) << error.what();
  }
}

// The exact error of a bad frame_observations.csv row: file, line, detail.
void expectFrameObservationError(const std::string& from, const std::string& to, const std::string& where,
                                 const std::string& detail) {
  testing::TempFolder run;
  writeFrontendOutputs(run.path(), sampleResult());
  const auto file = run / "frontend" / "frame_observations.csv";
  testing::replaceInFile(file, from, to);
  try {
    readFrontendOutputs(run.path());
    ADD_FAILURE() << "expected an InputError for '" << to << "'";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), file);
    EXPECT_EQ(error.where(), where);
    EXPECT_EQ(error.detail(), detail);
  }
}

TEST(FrontendOutputs, FrameObservationOfAFrameNotPosedIsRejectedWithItsLine) {
  expectFrameObservationError("\n21,1,", "\n12,1,", "line 8", "frame 12 is not a posed frame of frames.csv");
  expectFrameObservationError("\n21,1,", "\n25,1,", "line 8", "frame 25 is not a posed frame of frames.csv");
}

TEST(FrontendOutputs, FrameObservationOfAnUnknownLandmarkIsRejectedWithItsLine) {
  expectFrameObservationError("\n7,3,", "\n7,2,", "line 7", "unknown landmark 2");  // removed
  expectFrameObservationError("\n7,3,", "\n7,4,", "line 7", "unknown landmark 4");  // never existed
}

TEST(FrontendOutputs, FrameObservationsOutOfOrderOrRepeatedAreRejectedWithTheirLine) {
  expectFrameObservationError("\n3,3,", "\n3,0,", "line 5",
                              "rows must be sorted by frame, then landmark, each pair once");
  expectFrameObservationError("\n7,1,", "\n2,1,", "line 6",
                              "rows must be sorted by frame, then landmark, each pair once");
}

TEST(FrontendOutputs, FrameObservationsFileFollowsTheCsvRules) {
  expectFrameObservationError("\n7,1,", "\n\n7,1,", "line 6",
                              "blank line inside the table; expected a row 'frame,landmark,u,v'");
  expectFrameObservationError("7.5,8.5", "7.5,8.5,1", "line 7", "expected 4 columns (frame,landmark,u,v), got 5");
  expectFrameObservationError("frame,landmark,u,v", "frame,landmark,v,u", "line 1",
                              "expected the header 'frame,landmark,u,v', got 'frame,landmark,v,u'");
  {
    // CRLF line ends, blanks around cells and blank lines at the end are fine.
    testing::TempFolder run;
    writeFrontendOutputs(run.path(), sampleResult());
    const auto file = run / "frontend" / "frame_observations.csv";
    std::string text = testing::readText(file);
    std::string crlf;
    for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    testing::writeText(file, crlf + "\r\n  \r\n");
    testing::replaceInFile(file, "7,3,7.5,8.5", " 7 , 3,\t7.5 ,8.5 ");
    const FrontendResult read = readFrontendOutputs(run.path());
    ASSERT_EQ(read.frame_observations.size(), 7u);
    EXPECT_EQ(read.frame_observations[5].landmark, 3);
    EXPECT_EQ(read.frame_observations[5].v, 8.5f);
  }
  {
    testing::TempFolder run;
    writeFrontendOutputs(run.path(), sampleResult());
    testing::writeText(run / "frontend" / "frame_observations.csv", "\n");
    try {
      readFrontendOutputs(run.path());
      ADD_FAILURE() << "expected an InputError";
    } catch (const InputError& error) {
      EXPECT_EQ(error.where(), "line 1");
      EXPECT_EQ(error.detail(), "empty file; expected the header 'frame,landmark,u,v'");
    }
  }
}

TEST(FrontendOutputs, FrameObservationPixelMustBeAFloatNumber) {
  expectFrameObservationError("7.5,8.5", "7.5,abc", "line 7", "column 'v': expected a number, got 'abc'");
  expectFrameObservationError("7.5,8.5", "1e39,8.5", "line 7", "column 'u': expected a pixel coordinate, got '1e39'");
}

// A run folder written before segments were joined by vision (no link,
// scale_sigma, joined_to columns) still reads: every link then was the INS's.
TEST(FrontendOutputs, SegmentsWrittenBeforeTheVisionJoinStillRead) {
  testing::TempFolder run;
  writeFrontendOutputs(run.path(), sampleResult());
  const auto file = run / "frontend" / "segments.csv";
  std::ifstream in(file);
  std::string header, text, line;
  std::getline(in, header);
  text = "segment,first_frame,last_frame,keyframes,reference,linked,scale,qw,qx,qy,qz,x,y,z,ins_rms_m,note\n";
  while (std::getline(in, line)) {
    // Drop the three new cells before the note: link, scale_sigma, joined_to.
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    ASSERT_GE(cells.size(), 19u) << line;
    cells.erase(cells.begin() + 15, cells.begin() + 18);
    for (std::size_t i = 0; i < cells.size(); ++i) text += (i ? "," : "") + cells[i];
    text += "\n";
  }
  in.close();
  testing::writeText(file, text);
  const FrontendResult read = readFrontendOutputs(run.path());
  ASSERT_EQ(read.segments.size(), 2u);
  EXPECT_EQ(read.segments[0].link, SegmentLink::reference);
  EXPECT_EQ(read.segments[1].link, SegmentLink::ins);
  EXPECT_EQ(read.segments[1].joined_to, -1);
  EXPECT_EQ(read.segments[1].S_F_S.scale(), 0.75);
  EXPECT_EQ(read.segments[1].note, "linked into F through the INS; scale 0.75");
}

}  // namespace
}  // namespace hsmap
