#include "pipelines/sample_survey.h"

#include <gtest/gtest.h>

#include "core/survey/survey.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::readText;
using testing::TempFolder;

// Every regular file under `folder`, as paths relative to it, sorted.
std::vector<std::string> listFiles(const std::filesystem::path& folder) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file()) {
      files.push_back(std::filesystem::relative(entry.path(), folder).generic_string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(SampleSurvey, TwoWritesAreByteIdentical) {
  TempFolder temp("sample-determinism");
  const SampleSurveyContents first = writeSampleSurvey(temp / "a");
  writeSampleSurvey(temp / "b");
  const auto files_a = listFiles(temp / "a");
  const auto files_b = listFiles(temp / "b");
  ASSERT_EQ(files_a, files_b);
  // 75 frames + frames.csv + survey.yaml + cube.hdr/.raw + lines.csv + ins.csv.
  EXPECT_EQ(files_a.size(), 81u);
  std::vector<std::string> reported = first.files;
  std::sort(reported.begin(), reported.end());
  EXPECT_EQ(reported, files_a);
  for (const auto& file : files_a) {
    EXPECT_EQ(readText(temp / "a" / file), readText(temp / "b" / file)) << file;
  }
}

TEST(SampleSurvey, LoadsAndMatchesWhatItReports) {
  TempFolder temp("sample-load");
  const SampleSurveyContents contents = writeSampleSurvey(temp / "s");
  EXPECT_EQ(contents.folder, std::filesystem::absolute(temp / "s").lexically_normal());
  const Survey survey = loadSurvey(temp / "s");
  EXPECT_EQ(survey.rgb.frameCount(), contents.rgb_frames);
  EXPECT_EQ(survey.config.rgb.camera.width, contents.rgb_width);
  EXPECT_EQ(survey.config.rgb.camera.height, contents.rgb_height);
  EXPECT_EQ(survey.cube->header().lines, contents.uhi_lines);
  EXPECT_EQ(survey.cube->header().samples, contents.uhi_samples);
  EXPECT_EQ(survey.cube->header().bands, contents.uhi_bands);
  EXPECT_EQ(static_cast<int>(survey.ins.fixes.size()), contents.ins_fixes);
  EXPECT_TRUE(survey.warnings.empty());
  EXPECT_TRUE(survey.config.origin.has_value());

  // The cube carries a signal: lines differ and bands differ.
  Eigen::MatrixXf line0;
  Eigen::MatrixXf line50;
  survey.cube->readLine(0, line0);
  survey.cube->readLine(50, line50);
  EXPECT_GT((line0 - line50).cwiseAbs().maxCoeff(), 10.0f);
  EXPECT_GT(line0.maxCoeff(), line0.minCoeff() + 10.0f);
  EXPECT_GE(line0.minCoeff(), 0.0f);
  // Consecutive RGB frames differ (the texture moves) but stay similar.
  const double step = cv::norm(survey.rgb.frame(0), survey.rgb.frame(1), cv::NORM_L1);
  const double far = cv::norm(survey.rgb.frame(0), survey.rgb.frame(60), cv::NORM_L1);
  EXPECT_GT(step, 0.0);
  EXPECT_GT(far, step);
}

TEST(SampleSurvey, ReplacesAnExistingFolderAndLeavesNoPartialFolder) {
  TempFolder temp("sample-replace");
  testing::writeText(temp / "s" / "old.txt", "old");
  writeSampleSurvey(temp / "s/");
  EXPECT_FALSE(std::filesystem::exists(temp / "s" / "old.txt"));
  EXPECT_TRUE(std::filesystem::exists(temp / "s" / "survey.yaml"));
  EXPECT_FALSE(std::filesystem::exists(temp.path() / "s.partial"));
}

}  // namespace
}  // namespace hsmap
