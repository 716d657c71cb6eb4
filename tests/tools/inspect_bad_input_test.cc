// `hsmap inspect` on damaged surveys: every class of bad input found by
// mutation fuzzing ends with exit status 2 and exactly one line naming the
// file and the line or key, never a hang, a wrap-around or a silent accept.
// Each test damages a copy of the built-in sample survey the way the fuzzer
// did and checks the whole message.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/support/pristine_sample.h"
#include "tests/support/run_hsmap.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::pristineSample;
using testing::quoted;
using testing::readText;
using testing::replaceInFile;
using testing::runHsmap;
using testing::RunResult;
using testing::TempFolder;
using testing::writeText;


// 1-based line of the first occurrence of `needle` in `file`.
long long lineOf(const std::filesystem::path& file, const std::string& needle) {
  const std::string text = readText(file);
  const auto at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle << " not in " << file;
  return 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
}

class InspectBadInputTest : public ::testing::Test {
 protected:
  void SetUp() override { reset(); }
  // The pristine sample again, for a test that damages it more than once.
  void reset() {
    std::filesystem::remove_all(survey_);
    testing::copyFolder(pristineSample(), survey_);
  }

  RunResult inspect() { return runHsmap(temp_, "inspect " + quoted(survey_.string()), 60); }

  void expectError(const std::string& message) {
    const RunResult result = inspect();
    EXPECT_EQ(result.exit_status, 2) << result.err;
    EXPECT_EQ(result.err, "error: " + message + "\n");
    EXPECT_TRUE(result.out.empty()) << result.out;
  }

  std::filesystem::path yaml() const { return survey_ / "survey.yaml"; }
  std::string yamlKey(const std::string& needle, const std::string& key) {
    return yaml().string() + ":line " + std::to_string(lineOf(yaml(), needle)) + ", key " + key;
  }

  TempFolder temp_{"inspect-bad"};
  std::filesystem::path survey_ = temp_ / "survey";
};

// ---- size arithmetic ------------------------------------------------------

TEST_F(InspectBadInputTest, HeaderOffsetThatWouldWrapAroundIsRefused) {
  const auto hdr = survey_ / "uhi/cube.hdr";
  replaceInFile(hdr, "header offset = 0", "header offset = 18446744073708745216");
  // 90 lines x 64 samples x 16 bands x 2 bytes = 184320 bytes of data.
  expectError(hdr.string() + ":line " + std::to_string(lineOf(hdr, "header offset")) +
              ": key 'header offset': 18446744073708745216 bytes before 184320 bytes of data is "
              "beyond the largest possible file (2^63 bytes); expected the number of bytes that "
              "precede the data in the data file");
}

TEST_F(InspectBadInputTest, SizesWhoseProductOverflowsAreRefused) {
  const auto hdr = survey_ / "uhi/cube.hdr";
  replaceInFile(hdr, "bands = 16", "bands = 2147483647");
  replaceInFile(hdr, "lines = 90", "lines = 2147483647");
  std::string text = readText(hdr);
  // Drop the per-band lists, which would otherwise be the first complaint.
  for (const char* key : {"wavelength = {", "fwhm = {", "band names = {"}) {
    const auto at = text.find(key);
    if (at != std::string::npos) text.erase(at, text.find('}', at) + 2 - at);
  }
  writeText(hdr, text);
  expectError(hdr.string() + ":line " + std::to_string(lineOf(hdr, "bands =")) +
              ": key 'bands': samples 64 x lines 2147483647 x bands 2147483647 x 2 bytes per "
              "value is larger than any file can be (2^63 bytes); expected the sizes of a real "
              "raster");
}

// ---- silent accepts -------------------------------------------------------

TEST_F(InspectBadInputTest, SecondYamlDocumentIsRefused) {
  writeText(yaml(), readText(yaml()) + "...\nname: another survey\n");
  expectError(yaml().string() + ":line " + std::to_string(lineOf(yaml(), "name: another")) +
              ": a second YAML document starts here; expected the file to hold one document "
              "(remove what follows the first '---' / '...' document marker)");
}

TEST_F(InspectBadInputTest, TextThatIsNotUtf8IsRefused) {
  replaceInFile(yaml(), "name: hsmap-sample", "name: hsmap-\xFF\xFEsample");
  expectError(yaml().string() + ":line " + std::to_string(lineOf(yaml(), "name: ")) +
              ": byte 0xFF in column 13 is not UTF-8; expected UTF-8 text");
}

TEST_F(InspectBadInputTest, NulByteInAFrameNameIsRefused) {
  const auto frames = survey_ / "rgb/frames.csv";
  std::string text = readText(frames);
  text.replace(text.find("frame_0003.png"), 14, std::string("frame_0003\0.png", 15));
  writeText(frames, text);
  expectError(frames.string() + ":line 5: control character 0x00 (NUL) in column 11; expected "
              "text (is this a binary or damaged file?)");
}

TEST_F(InspectBadInputTest, ControlCharacterAsYamlEscapeIsRefused) {
  replaceInFile(yaml(), "name: hsmap-sample", "name: \"hsmap\\0sample\"");
  expectError(yamlKey("name: ", "name") +
              ": expected printable text, got 'hsmap\\x00sample' (it holds a control character)");
}

TEST_F(InspectBadInputTest, EveryFrameHeaderIsChecked) {
  const auto frames = survey_ / "rgb/frames.csv";
  const auto frame = [&](int i) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%04d.png", i);
    return std::string(name);
  };
  const auto expectFrameError = [&](int i, const std::string& detail) {
    expectError(frames.string() + ":line " + std::to_string(i + 2) + ": column 'file': image '" +
                frame(i) + "' is " + detail);
  };
  // Empty.
  writeText(survey_ / "rgb" / frame(40), "");
  expectFrameError(40, "an empty file (" + (survey_ / "rgb" / frame(40)).string() + ")");
  // Not an image.
  writeText(survey_ / "rgb" / frame(40), "root:x:0:0:root:/root:/bin/bash\n");
  expectFrameError(40, "not a PNG or JPEG image (it starts with 'root:x:0') (" +
                           (survey_ / "rgb" / frame(40)).string() + ")");
  // A valid image of another size.
  cv::imwrite((survey_ / "rgb" / frame(40)).string(), cv::Mat(100, 80, CV_8UC3, cv::Scalar(9)));
  expectFrameError(40, "80x100 pixels but " + yaml().string() +
                           " gives rgb.camera width 160, height 120");
  // A truncated PNG (signature only).
  writeText(survey_ / "rgb" / frame(40), "\x89PNG\r\n\x1A\n");
  expectFrameError(40, "a damaged PNG image (no IHDR chunk after the signature) (" +
                           (survey_ / "rgb" / frame(40)).string() + ")");
  // A listed path that is a device.
  std::filesystem::copy_file(pristineSample() / "rgb" / frame(40), survey_ / "rgb" / frame(40),
                             std::filesystem::copy_options::overwrite_existing);
  replaceInFile(frames, frame(60), "/dev/zero");
  expectError(frames.string() + ":line 62: column 'file': image '/dev/zero' is a character "
              "device; expected a PNG or JPEG image file (/dev/zero)");
}

TEST_F(InspectBadInputTest, NonFiniteFwhmIsRefused) {
  const auto hdr = survey_ / "uhi/cube.hdr";
  std::string text = readText(hdr);
  const auto at = text.find("fwhm = {");
  ASSERT_NE(at, std::string::npos);
  const auto first = text.find_first_of("0123456789", at);
  text.replace(first, text.find_first_of(",}", first) - first, "nan");
  writeText(hdr, text);
  expectError(hdr.string() + ":line " + std::to_string(lineOf(hdr, "fwhm")) +
              ": key 'fwhm': expected a finite number as item 1, found 'nan'");
}

TEST_F(InspectBadInputTest, NonPhysicalInsValuesAreRefused) {
  const auto ins = survey_ / "nav/ins.csv";
  const std::string pristine = readText(ins);
  const auto row2 = pristine.find('\n') + 1;
  // Time of the first fix: 1e300.
  std::string text = pristine;
  text.replace(row2, text.find(',', row2) - row2, "1e300");
  writeText(ins, text);
  expectError(ins.string() + ":line 2: column 't': expected a time in [-4e9, 4e9] s, got 1e+300 "
              "(seconds on the survey's clock; a float64 beyond 4e9 s cannot hold microseconds)");
  // Depth of the first fix: 1e308.
  text = pristine;
  std::size_t depth = row2;
  for (int comma = 0; comma < 3; ++comma) depth = text.find(',', depth) + 1;
  text.replace(depth, text.find(',', depth) - depth, "1e308");
  writeText(ins, text);
  expectError(ins.string() + ":line 2: column 'depth': expected a depth in [-10000, 12000] m, got "
              "1e+308");
}

TEST_F(InspectBadInputTest, ImpossibleInsJumpIsAnErrorAndAPlausibleOneAWarning) {
  const auto ins = survey_ / "nav/ins.csv";
  const std::string pristine = readText(ins);
  // Third fix (line 4): longitude from ~5 to 91 degrees, one second later.
  const auto row4 = [&] {
    std::size_t at = 0;
    for (int line = 1; line < 4; ++line) at = pristine.find('\n', at) + 1;
    return at;
  }();
  const auto lon_start = pristine.find(',', pristine.find(',', row4) + 1) + 1;
  std::string text = pristine;
  text.replace(lon_start, text.find(',', lon_start) - lon_start, "91");
  writeText(ins, text);
  const RunResult impossible = inspect();
  EXPECT_EQ(impossible.exit_status, 2);
  EXPECT_EQ(impossible.err.rfind("error: " + ins.string() + ":line 4: the position jumps ", 0), 0u)
      << impossible.err;
  EXPECT_NE(impossible.err.find(" m in 1.000 s from the previous fix ("), std::string::npos);
  EXPECT_NE(impossible.err.find("; expected a vehicle's track (no underwater vehicle or acoustic "
                                "fix moves more than 1 km at over 50 m/s)\n"),
            std::string::npos)
      << impossible.err;
  EXPECT_EQ(std::count(impossible.err.begin(), impossible.err.end(), '\n'), 1);

  // Depth of the third fix 20 m deeper: a jump that a real log can hold.
  text = pristine;
  std::size_t depth = row4;
  for (int comma = 0; comma < 3; ++comma) depth = text.find(',', depth) + 1;
  const double old_depth = std::stod(text.substr(depth, text.find(',', depth) - depth));
  text.replace(depth, text.find(',', depth) - depth, std::to_string(old_depth + 20.0));
  writeText(ins, text);
  const RunResult plausible = inspect();
  EXPECT_EQ(plausible.exit_status, 0) << plausible.err;
  EXPECT_NE(plausible.out.find(ins.string() + ":line 4: the depth jumps 20.0 m in 1.000 s from "
                               "the previous fix (20 m/s), more than a vehicle moves; "
                               "geo-referencing will treat it as an outlier"),
            std::string::npos)
      << plausible.out;
}

// ---- hangs and unbounded reads --------------------------------------------

TEST_F(InspectBadInputTest, NamedPipesAreRefusedWithoutBlocking) {
  for (const auto& [relative, needle, key, expected] :
       {std::tuple{"rgb/frames.csv", "frames: ", "rgb.frames", "the frame table (file,t)"},
        std::tuple{"nav/ins.csv", "file: ", "ins.file", "the INS table (t,lat,lon,depth...)"},
        std::tuple{"uhi/cube.hdr", "cube: ", "uhi.cube", "an ENVI header (.hdr)"}}) {
    SCOPED_TRACE(relative);
    reset();
    const auto path = survey_ / relative;
    std::filesystem::remove(path);
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    expectError(yamlKey(needle, key) + ": the file '" + path.string() +
                "' is a named pipe (FIFO); expected " + expected);
  }
}

TEST_F(InspectBadInputTest, DevicesAndMissingFilesAreReportedAtTheirKey) {
  replaceInFile(yaml(), "frames: rgb/frames.csv", "frames: /dev/zero");
  expectError(yamlKey("frames: ", "rgb.frames") +
              ": the file '/dev/zero' is a character device; expected the frame table (file,t)");
  reset();
  replaceInFile(yaml(), "frames: rgb/frames.csv", "frames: /dev/null");
  expectError(yamlKey("frames: ", "rgb.frames") +
              ": the file '/dev/null' is a character device; expected the frame table (file,t)");
  reset();
  replaceInFile(yaml(), "lines: uhi/lines.csv", "lines: 2.5");
  expectError(yamlKey("lines: ", "uhi.lines") + ": the file '" + (survey_ / "2.5").string() +
              "' not found; expected the scan-line table (line,t)");
}

TEST_F(InspectBadInputTest, OversizedTextInputIsRefusedBeforeReading) {
  writeText(yaml(), readText(yaml()) + "# " + std::string(2u << 20, 'x') + "\n");
  expectError(yaml().string() +
              ": the file is 2.0 MiB; expected a text file of at most 1.0 MiB");
}

// ---- messages -------------------------------------------------------------

TEST_F(InspectBadInputTest, LongValuesAreCutAndEscaped) {
  const auto ins = survey_ / "nav/ins.csv";
  std::string text = readText(ins);
  const auto row2 = text.find('\n') + 1;
  const auto lat = text.find(',', row2) + 1;
  text.replace(lat, text.find(',', lat) - lat, std::string(100000, '7') + "x");
  writeText(ins, text);
  expectError(ins.string() + ":line 2: column 'lat': expected a number, got '" +
              std::string(60, '7') + "... (100001 bytes)'");

  const auto hdr = survey_ / "uhi/cube.hdr";
  reset();
  replaceInFile(hdr, "interleave = bil", "interleave = b\xE9l\\");
  expectError(hdr.string() + ":line " + std::to_string(lineOf(hdr, "interleave")) +
              ": key 'interleave': expected bsq, bil or bip, found 'b\\xE9l\\\\'");
}

TEST_F(InspectBadInputTest, UndecodableVideoGivesOneLine) {
  writeText(survey_ / "rgb/dive.mp4", std::string(4096, '\x42'));
  std::string text = readText(yaml());
  const auto at = text.find("frames: rgb/frames.csv");
  text.replace(at, 22, "video: rgb/dive.mp4\n  start_time: 36000\n  fps: 25");
  writeText(yaml(), text);
  const RunResult result = inspect();
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_EQ(result.err.rfind("error: " + (survey_ / "rgb/dive.mp4").string() +
                                 ": cannot open the video (unsupported container or codec?)",
                             0),
            0u)
      << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

TEST_F(InspectBadInputTest, OldMacLineEndsAreRead) {
  std::string text = readText(yaml());
  std::replace(text.begin(), text.end(), '\n', '\r');
  writeText(yaml(), text);
  const RunResult result = inspect();
  EXPECT_EQ(result.exit_status, 0) << result.err;
  EXPECT_NE(result.out.find("survey 'hsmap-sample'"), std::string::npos) << result.out;
}

}  // namespace
}  // namespace hsmap
