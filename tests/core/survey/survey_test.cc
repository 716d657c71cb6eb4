#include "core/survey/survey.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/videoio.hpp>

#include "core/io/envi_header.h"
#include "core/survey/number_text.h"
#include "core/util/input_error.h"
#include "pipelines/sample_survey.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::readText;
using testing::replaceInFile;
using testing::TempFolder;
using testing::writeText;

// The built-in sample survey, written once for this program (static objects
// are destroyed, and the folder removed, at exit).
const std::filesystem::path& pristineSample() {
  static const TempFolder folder("survey-pristine");
  static const std::filesystem::path sample = [] {
    writeSampleSurvey(folder / "sample");
    return folder / "sample";
  }();
  return sample;
}

// Each test gets a fresh copy of the built-in sample survey to damage.
class LoadSurveyTest : public ::testing::Test {
 protected:
  TempFolder temp_{"survey"};
  std::filesystem::path survey_ = temp_ / "sample";

  void SetUp() override { testing::copyFolder(pristineSample(), survey_); }

  // loadSurvey must throw InputError naming `file`, with what() exactly
  // "<file>:<rest>".
  void expectError(const std::filesystem::path& file, const std::string& rest) {
    try {
      loadSurvey(survey_);
      FAIL() << "no InputError; expected " << file.string() << ":" << rest;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file);
      EXPECT_EQ(std::string(e.what()), file.string() + ":" + rest);
    }
  }
};

TEST_F(LoadSurveyTest, SampleSurveyLoadsWithItsCountsBandsAndSpans) {
  const Survey survey = loadSurvey(survey_);
  EXPECT_EQ(survey.config.name, "hsmap-sample");
  EXPECT_EQ(survey.rgb.frameCount(), 75);
  EXPECT_FALSE(survey.rgb.isVideo());
  EXPECT_EQ(survey.rgb.time(0), 36000.0);
  EXPECT_DOUBLE_EQ(survey.rgb.time(74), 36000.0 + 74.0 / 25.0);
  EXPECT_EQ(survey.rgb.frame(10).size(), cv::Size(160, 120));

  ASSERT_NE(survey.cube, nullptr);
  EXPECT_EQ(survey.cube->header().lines, 90);
  EXPECT_EQ(survey.cube->header().samples, 64);
  EXPECT_EQ(survey.cube->header().bands, 16);
  EXPECT_EQ(survey.cube->header().data_type, EnviDataType::uint16);
  EXPECT_EQ(survey.cube->header().interleave, EnviInterleave::bil);
  ASSERT_EQ(survey.wavelengths_nm.size(), 16u);
  EXPECT_DOUBLE_EQ(survey.wavelengths_nm.front(), 400.0);
  EXPECT_DOUBLE_EQ(survey.wavelengths_nm.back(), 800.0);
  ASSERT_EQ(survey.line_times.size(), 90u);
  EXPECT_EQ(survey.line_times.front(), 36000.0);
  EXPECT_DOUBLE_EQ(survey.line_times.back(), 36000.0 + 89.0 / 30.0);

  EXPECT_TRUE(survey.ins.has_attitude);
  ASSERT_EQ(survey.ins.fixes.size(), 6u);
  EXPECT_EQ(survey.ins.fixes.front().t, 35999.0);
  EXPECT_EQ(survey.ins.fixes.back().t, 36004.0);

  EXPECT_TRUE(survey.origin_from_config);
  EXPECT_EQ(survey.origin.lat_deg, 43.0);
  EXPECT_EQ(survey.origin.lon_deg, 5.0);
  EXPECT_FALSE(survey.truth.present);
  EXPECT_TRUE(survey.warnings.empty());
  EXPECT_EQ(survey.lines_path, survey_ / "uhi/lines.csv");
}

TEST_F(LoadSurveyTest, MissingFolder) {
  const auto absent = temp_ / "absent";
  try {
    loadSurvey(absent);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        absent.string() + ": survey folder not found (expected a folder holding survey.yaml)");
  }
}

TEST_F(LoadSurveyTest, BrokenEnviHeaderNamesTheHeaderAndWhere) {
  const auto hdr = survey_ / "uhi/cube.hdr";
  std::string text = readText(hdr);
  const auto at = text.find("samples");
  ASSERT_NE(at, std::string::npos);
  const auto end = text.find('\n', at);
  text.replace(at, end - at, "samples = sixty-four");
  writeText(hdr, text);
  try {
    loadSurvey(survey_);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), hdr);
    EXPECT_FALSE(e.where().empty()) << e.what();  // a line or a key
    EXPECT_NE(std::string(e.what()).find(hdr.string()), std::string::npos);
  }
}

TEST_F(LoadSurveyTest, TruncatedCubeNamesTheDataFile) {
  const auto raw = survey_ / "uhi/cube.raw";
  std::filesystem::resize_file(raw, std::filesystem::file_size(raw) - 100);
  try {
    loadSurvey(survey_);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), raw) << e.what();
    EXPECT_NE(std::string(e.what()).find(raw.string()), std::string::npos);
  }
}

TEST_F(LoadSurveyTest, UnsortedTimeStamps) {
  const auto lines = survey_ / "uhi/lines.csv";
  std::vector<double> times = readLinesCsv(lines);
  times[5] = 36000.1;  // earlier than line 4's 36000.133...
  writeLinesCsv(lines, times);
  expectError(lines, "line 7: time 't' = 36000.1 is earlier than the previous row's " +
                         formatDouble(times[4]) + ": rows must be in time order");
}

TEST_F(LoadSurveyTest, DuplicatedTimeStamps) {
  const auto frames_csv = survey_ / "rgb/frames.csv";
  std::vector<FrameRow> frames = readFramesCsv(frames_csv);
  frames[3].t = frames[2].t;
  writeFramesCsv(frames_csv, frames);
  expectError(frames_csv, "line 5: time 't' = " + formatDouble(frames[2].t) +
                              " equals the previous row's: duplicated time stamp");
}

TEST_F(LoadSurveyTest, MissingFrameFile) {
  std::filesystem::remove(survey_ / "rgb/frame_0010.png");
  expectError(survey_ / "rgb/frames.csv",
              "line 12: column 'file': image 'frame_0010.png' not found (expected the file " +
                  (survey_ / "rgb/frame_0010.png").string() + ")");
}

TEST_F(LoadSurveyTest, NanInTheIns) {
  const auto ins = survey_ / "nav/ins.csv";
  std::string text = readText(ins);
  // Row 3 (line 4): replace its latitude by nan.
  std::size_t at = 0;
  for (int newline = 0; newline < 3; ++newline) at = text.find('\n', at) + 1;
  const auto lat_start = text.find(',', at) + 1;
  const auto lat_end = text.find(',', lat_start);
  text.replace(lat_start, lat_end - lat_start, "nan");
  writeText(ins, text);
  expectError(ins, "line 4: column 'lat': expected a finite number, got 'nan'");
}

TEST_F(LoadSurveyTest, UnknownYamlKey) {
  const auto yaml = survey_ / "survey.yaml";
  replaceInFile(yaml, "  time_offset_s: 0\n", "  time_offset_s: 0\n  time_ofset_sigma_s: 0.1\n");
  try {
    loadSurvey(survey_);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), yaml);
    // The line depends on the writer's layout: find it in the file.
    const std::string text = readText(yaml);
    const auto at = text.find("time_ofset_sigma_s");
    const long long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
    EXPECT_EQ(
        std::string(e.what()),
        yaml.string() + ":line " + std::to_string(line) +
            ", key uhi.time_ofset_sigma_s: unknown key; expected one of: cube, lines, camera, "
            "camera_sigma, extrinsic, time_offset_s, time_offset_sigma_s");
  }
}

TEST_F(LoadSurveyTest, LinesCsvWithFewerRowsThanTheCube) {
  const auto lines = survey_ / "uhi/lines.csv";
  std::string text = readText(lines);
  text.erase(text.rfind('\n', text.size() - 2) + 1);  // drop the last row
  writeText(lines, text);
  expectError(lines, "line 90: the table ends at scan line 88 (89 rows), but the cube " +
                         (survey_ / "uhi/cube.hdr").string() +
                         " has 90 lines; expected one row per scan line");
}

TEST_F(LoadSurveyTest, LinesCsvWithMoreRowsThanTheCube) {
  const auto lines = survey_ / "uhi/lines.csv";
  writeText(lines, readText(lines) + "90,36003.1\n");
  expectError(lines, "line 92: row for scan line 90, but the cube " +
                         (survey_ / "uhi/cube.hdr").string() +
                         " has 90 lines; expected one row per scan line (91 rows given)");
}

TEST_F(LoadSurveyTest, CubeSamplesMustMatchTheCamera) {
  replaceInFile(survey_ / "survey.yaml", "samples: 64", "samples: 65");
  expectError(
      survey_ / "uhi/cube.hdr",
      "key samples: the cube has 64 samples per line but " + (survey_ / "survey.yaml").string() +
          " gives uhi.camera.samples 65; the camera model must describe every pixel of a line");
}

TEST_F(LoadSurveyTest, WavelengthsAreRequired) {
  const auto hdr = survey_ / "uhi/cube.hdr";
  EnviHeader header = readEnviHeader(hdr);
  header.wavelength.clear();
  header.fwhm.clear();
  header.wavelength_units.clear();
  writeEnviHeader(hdr, header);
  expectError(hdr,
              "key wavelength: missing: hsmap needs the wavelength of each of the 16 bands to "
              "label its products");
}

TEST_F(LoadSurveyTest, WavelengthsInMicrometresAreConvertedToNanometres) {
  const auto hdr = survey_ / "uhi/cube.hdr";
  EnviHeader header = readEnviHeader(hdr);
  const std::vector<double> nm = header.wavelength;
  for (double& wavelength : header.wavelength) wavelength /= 1000.0;
  header.wavelength_units = "Micrometers";
  writeEnviHeader(hdr, header);
  const Survey survey = loadSurvey(survey_);
  ASSERT_EQ(survey.wavelengths_nm.size(), nm.size());
  for (std::size_t b = 0; b < nm.size(); ++b) EXPECT_NEAR(survey.wavelengths_nm[b], nm[b], 1e-9);

  header.wavelength_units = "Wavenumber";
  writeEnviHeader(hdr, header);
  expectError(hdr,
              "key wavelength units: unsupported units 'Wavenumber'; expected Nanometers or "
              "Micrometers");
}

TEST_F(LoadSurveyTest, FrameSizeMustMatchTheCamera) {
  replaceInFile(survey_ / "survey.yaml", "width: 160", "width: 161");
  expectError(survey_ / "rgb/frames.csv", "line 2: column 'file': image 'frame_0000.png' is "
                                         "160x120 pixels but " +
                                             (survey_ / "survey.yaml").string() +
                                             " gives rgb.camera width 161, height 120");
}

TEST_F(LoadSurveyTest, StreamsDisjointFromTheInsAreAnError) {
  InsTable ins = readInsCsv(survey_ / "nav/ins.csv");
  for (InsFix& fix : ins.fixes) fix.t += 1000.0;
  writeInsCsv(survey_ / "nav/ins.csv", ins);
  expectError(survey_ / "rgb/frames.csv",
              " the RGB time span [36000.000, 36002.960] s does not overlap the INS time span "
              "[36999.000, 37004.000] s of " +
                  (survey_ / "nav/ins.csv").string() +
                  ": nothing could be geo-referenced (are both on the same clock?)");
}

TEST_F(LoadSurveyTest, PartialInsCoverageIsAWarning) {
  InsTable ins = readInsCsv(survey_ / "nav/ins.csv");
  ins.fixes.resize(4);  // the last fix is now at 36002 s
  writeInsCsv(survey_ / "nav/ins.csv", ins);
  const Survey survey = loadSurvey(survey_);
  ASSERT_EQ(survey.warnings.size(), 2u);
  EXPECT_EQ(survey.warnings[0],
            "the RGB time span [36000.000, 36002.960] s is not fully covered by the INS span "
            "[35999.000, 36002.000] s: 0.960 s after the last fix (poses there are extrapolated)");
  EXPECT_EQ(survey.warnings[1],
            "the UHI time span [36000.000, 36002.967] s is not fully covered by the INS span "
            "[35999.000, 36002.000] s: 0.967 s after the last fix (poses there are extrapolated)");
}

TEST_F(LoadSurveyTest, OriginDefaultsToTheFirstInsFix) {
  const auto yaml = survey_ / "survey.yaml";
  SurveyConfig config = readSurveyConfig(yaml);
  config.origin.reset();
  writeSurveyConfig(yaml, config);
  const Survey survey = loadSurvey(survey_);
  EXPECT_FALSE(survey.origin_from_config);
  EXPECT_EQ(survey.origin.lat_deg, survey.ins.fixes.front().lat_deg);
  EXPECT_EQ(survey.origin.lon_deg, survey.ins.fixes.front().lon_deg);
  EXPECT_EQ(survey.origin.depth_m, survey.ins.fixes.front().depth_m);
}

TEST_F(LoadSurveyTest, VideoSurveyLoads) {
  // Re-encode the sample's frames as an MJPEG video (OpenCV's built-in codec).
  const RgbFrameSource frames = RgbFrameSource::fromFrameList(survey_ / "rgb/frames.csv");
  const auto video = survey_ / "rgb/dive.avi";
  {
    cv::VideoWriter writer(video.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25.0,
                           cv::Size(160, 120));
    ASSERT_TRUE(writer.isOpened());
    for (int i = 0; i < frames.frameCount(); ++i) writer.write(frames.frame(i));
  }
  SurveyConfig config = readSurveyConfig(survey_ / "survey.yaml");
  config.rgb.frames.clear();
  config.rgb.video = RgbVideoConfig{"rgb/dive.avi", 36000.0, 25.0};
  writeSurveyConfig(survey_ / "survey.yaml", config);

  const Survey survey = loadSurvey(survey_);
  EXPECT_TRUE(survey.rgb.isVideo());
  EXPECT_EQ(survey.rgb.sourcePath(), video);
  ASSERT_EQ(survey.rgb.frameCount(), 75);
  EXPECT_EQ(survey.rgb.time(0), 36000.0);
  EXPECT_DOUBLE_EQ(survey.rgb.time(74), 36000.0 + 74.0 / 25.0);
  EXPECT_EQ(survey.rgb.frame(30).size(), cv::Size(160, 120));
  EXPECT_TRUE(survey.warnings.empty());
}

TEST_F(LoadSurveyTest, TruthFolderIsDetected) {
  writeText(survey_ / "truth/rgb_poses.csv", "t,x,y,z,qw,qx,qy,qz\n");
  writeText(survey_ / "truth/calibration.yaml", "format: hsmap-truth/1\n");
  const Survey survey = loadSurvey(survey_);
  EXPECT_TRUE(survey.truth.present);
  EXPECT_EQ(survey.truth.found_files,
            (std::vector<std::string>{"rgb_poses.csv", "calibration.yaml"}));
  EXPECT_EQ(survey.truth.missing_files,
            (std::vector<std::string>{"uhi_poses.csv", "scene.ply", "reflectance.hdr",
                                      "reflectance.raw"}));
}

}  // namespace
}  // namespace hsmap
