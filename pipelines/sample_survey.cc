#include "pipelines/sample_survey.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "core/geometry/local_ned_frame.h"
#include "core/io/envi_header.h"
#include "core/io/envi_writer.h"
#include "core/survey/csv_table.h"
#include "core/survey/survey_config.h"

namespace hsmap {
namespace {

// Sizes and rates of the sample (see sample_survey.h).
constexpr double kStartTime = 36000.0;  // s, 10:00:00 on the survey clock
constexpr int kFrames = 75;
constexpr double kFrameRate = 25.0;
constexpr int kWidth = 160;
constexpr int kHeight = 120;
constexpr double kFocalPx = 150.0;
constexpr int kLines = 90;
constexpr double kLineRate = 30.0;
constexpr int kSamples = 64;
constexpr double kUhiFocalPx = 64.0;
constexpr int kBands = 16;
constexpr int kInsFixes = 6;
constexpr double kAltitude = 2.0;         // m, camera above the seabed
constexpr double kSpeed = 0.5;            // m/s, northwards
constexpr double kDepth = 20.0;           // m, vehicle depth
constexpr double kUhiOffsetAcross = 0.1;  // m, T_C_U translation along x_C (starboard)
constexpr double kOriginLat = 43.0;
constexpr double kOriginLon = 5.0;

// Seabed texture in pixels of the RGB camera's ground sampling (fx / altitude px per metre).
constexpr double kTexturePxPerM = kFocalPx / kAltitude;
constexpr int kTextureCols = 200;
constexpr int kTextureRows = 272;
constexpr double kTextureLeft = (kTextureCols - kWidth) / 2.0;
constexpr double kTextureTop0 = kTextureRows - kHeight - 10.0;

// Row (in the texture) of the top edge of the RGB image at time t: the
// vehicle moves north, so the window slides towards row 0.
double windowTop(double t) { return kTextureTop0 - kSpeed * kTexturePxPerM * (t - kStartTime); }

double wavelengthNm(int band) { return 400.0 + 400.0 * band / (kBands - 1); }

// Two reflectance spectra (sand; algae with a green peak and a red edge) and
// the two-way transmission of ~2 m of coastal water.
double sandReflectance(double nm) { return 0.15 + 0.25 * (nm - 400.0) / 400.0; }
double algaeReflectance(double nm) {
  return 0.05 + 0.08 * std::exp(-std::pow((nm - 550.0) / 40.0, 2)) +
         0.35 / (1.0 + std::exp(-(nm - 700.0) / 15.0));
}
double waterTransmission(double nm) {
  const double red = std::max(0.0, (nm - 550.0) / 250.0);
  const double attenuation_per_m = 0.05 + 0.5 * red * red;
  return std::exp(-attenuation_per_m * 2.0 * kAltitude);
}

struct Texture {
  cv::Mat detail;  // CV_32F in [0.3, 1]: brightness
  cv::Mat mix;     // CV_32F in [0, 1]: fraction of algae
};

Texture makeTexture() {
  cv::RNG rng(20240611);  // fixed seed: the sample is deterministic
  Texture texture;
  cv::Mat noise(kTextureRows, kTextureCols, CV_32F);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, texture.detail, cv::Size(0, 0), 1.5);
  cv::normalize(texture.detail, texture.detail, 0.3, 1.0, cv::NORM_MINMAX);
  cv::Mat blobs(kTextureRows, kTextureCols, CV_32F);
  rng.fill(blobs, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(blobs, texture.mix, cv::Size(0, 0), 12.0);
  cv::normalize(texture.mix, texture.mix, 0.0, 1.0, cv::NORM_MINMAX);
  return texture;
}

// The texture as the RGB camera sees it: sand is pale yellow, algae green-brown.
cv::Mat colourTexture(const Texture& texture) {
  const cv::Vec3f sand_bgr(150.0f, 215.0f, 230.0f);
  const cv::Vec3f algae_bgr(40.0f, 120.0f, 70.0f);
  cv::Mat bgr(kTextureRows, kTextureCols, CV_32FC3);
  for (int r = 0; r < kTextureRows; ++r) {
    for (int c = 0; c < kTextureCols; ++c) {
      const float m = texture.mix.at<float>(r, c);
      const float d = texture.detail.at<float>(r, c);
      bgr.at<cv::Vec3f>(r, c) = d * ((1.0f - m) * sand_bgr + m * algae_bgr);
    }
  }
  return bgr;
}

cv::Mat renderFrame(const cv::Mat& colour, double t) {
  const cv::Matx23d shift(1, 0, -kTextureLeft, 0, 1, -windowTop(t));
  cv::Mat frame;
  cv::warpAffine(colour, frame, shift, cv::Size(kWidth, kHeight), cv::INTER_LINEAR,
                 cv::BORDER_REFLECT);
  frame.convertTo(frame, CV_8UC3);
  return frame;
}

// One scan line, band-major (out[b * samples + s]), in digital numbers.
std::vector<float> renderScanLine(const Texture& texture, double t) {
  // The line lies under the image's centre row, shifted across-track by T_C_U.
  cv::Mat map_x(1, kSamples, CV_32F);
  cv::Mat map_y(1, kSamples, CV_32F);
  const double px_per_sample = kTexturePxPerM * kAltitude / kUhiFocalPx;
  const double centre_col = kTextureLeft + (kWidth - 1) / 2.0 + kUhiOffsetAcross * kTexturePxPerM;
  for (int s = 0; s < kSamples; ++s) {
    map_x.at<float>(0, s) =
        static_cast<float>(centre_col + (s - (kSamples - 1) / 2.0) * px_per_sample);
    map_y.at<float>(0, s) = static_cast<float>(windowTop(t) + (kHeight - 1) / 2.0);
  }
  cv::Mat detail;
  cv::Mat mix;
  cv::remap(texture.detail, detail, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  cv::remap(texture.mix, mix, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  std::vector<float> line(static_cast<std::size_t>(kBands * kSamples));
  for (int b = 0; b < kBands; ++b) {
    const double nm = wavelengthNm(b);
    for (int s = 0; s < kSamples; ++s) {
      const double m = mix.at<float>(0, s);
      const double reflectance = (1.0 - m) * sandReflectance(nm) + m * algaeReflectance(nm);
      const double dn = 6000.0 * detail.at<float>(0, s) * reflectance * waterTransmission(nm);
      line[static_cast<std::size_t>(b * kSamples + s)] = static_cast<float>(std::round(dn));
    }
  }
  return line;
}

SurveyConfig sampleConfig() {
  SurveyConfig config;
  config.name = "hsmap-sample";
  config.rgb.frames = "rgb/frames.csv";
  config.rgb.camera.width = kWidth;
  config.rgb.camera.height = kHeight;
  config.rgb.camera.fx = kFocalPx;
  config.rgb.camera.fy = kFocalPx;
  config.rgb.camera.cx = (kWidth - 1) / 2.0;
  config.rgb.camera.cy = (kHeight - 1) / 2.0;
  config.uhi.cube = "uhi/cube.hdr";
  config.uhi.lines = "uhi/lines.csv";
  config.uhi.camera.samples = kSamples;
  config.uhi.camera.f = kUhiFocalPx;
  config.uhi.camera.cx = (kSamples - 1) / 2.0;
  config.uhi.T_C_U.translation_m = Eigen::Vector3d(kUhiOffsetAcross, 0.0, 0.0);
  config.ins.file = "nav/ins.csv";
  // Down-looking camera: z_C = z_B (down), x_C = y_B (starboard), so the
  // image's up direction is the vehicle's forward: a rotation of 90 deg about z_B.
  config.ins.T_B_C.rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ()));
  config.ins.T_B_C.translation_m = Eigen::Vector3d(0.5, 0.0, 0.3);
  config.origin = GeodeticPoint{kOriginLat, kOriginLon, 0.0};
  return config;
}

InsTable sampleIns() {
  const LocalNedFrame world(GeodeticPoint{kOriginLat, kOriginLon, 0.0});
  InsTable ins;
  ins.has_attitude = true;
  for (int k = 0; k < kInsFixes; ++k) {
    InsFix fix;
    fix.t = kStartTime - 1.0 + k;
    // p_W = (north, east, down) of the vehicle, straight north at kSpeed.
    const Eigen::Vector3d p_W(kSpeed * (fix.t - kStartTime), 0.0,
                              kDepth + 0.05 * std::sin(0.9 * k));
    const GeodeticPoint position = world.toGeodetic(p_W);
    fix.lat_deg = position.lat_deg;
    fix.lon_deg = position.lon_deg;
    fix.depth_m = position.depth_m;
    fix.roll_deg = 0.5 * std::sin(0.7 * k);
    fix.pitch_deg = 0.3 * std::cos(0.5 * k);
    fix.heading_deg = 0.1 * k;
    ins.fixes.push_back(fix);
  }
  return ins;
}

EnviHeader sampleCubeHeader() {
  EnviHeader header;
  header.samples = kSamples;
  header.lines = kLines;
  header.bands = kBands;
  header.header_offset = 0;
  header.data_type = EnviDataType::uint16;
  header.interleave = EnviInterleave::bil;
  header.byte_order = 0;
  for (int b = 0; b < kBands; ++b) {
    header.wavelength.push_back(wavelengthNm(b));
    header.fwhm.push_back(25.0);
  }
  header.wavelength_units = "Nanometers";
  header.description = "hsmap sample survey: UHI radiance in digital numbers (not a simulation)";
  return header;
}

std::filesystem::path targetFolder(const std::filesystem::path& folder) {
  std::filesystem::path target = std::filesystem::absolute(folder).lexically_normal();
  if (target.filename().empty()) target = target.parent_path();  // "dir/" -> "dir"
  if (target.filename().empty() || target == target.root_path()) {
    throw std::invalid_argument("writeSampleSurvey: '" + folder.string() +
                                "' is not a folder name");
  }
  return target;
}

}  // namespace

SampleSurveyContents writeSampleSurvey(const std::filesystem::path& folder) {
  const std::filesystem::path target = targetFolder(folder);
  std::filesystem::path partial = target;
  partial += ".partial";
  std::filesystem::remove_all(partial);  // left over by an interrupted call
  std::filesystem::create_directories(partial / "rgb");
  std::filesystem::create_directories(partial / "uhi");
  std::filesystem::create_directories(partial / "nav");

  SampleSurveyContents contents;
  contents.folder = target;
  const SurveyConfig config = sampleConfig();
  writeSurveyConfig(partial / "survey.yaml", config);
  contents.files.push_back("survey.yaml");

  const Texture texture = makeTexture();
  const cv::Mat colour = colourTexture(texture);
  std::vector<FrameRow> frames;
  for (int i = 0; i < kFrames; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%04d.png", i);
    const double t = kStartTime + i / kFrameRate;
    const std::filesystem::path image = partial / "rgb" / name;
    if (!cv::imwrite(image.string(), renderFrame(colour, t), {cv::IMWRITE_PNG_COMPRESSION, 1})) {
      throw std::runtime_error("writeSampleSurvey: cannot write " + image.string());
    }
    frames.push_back({name, t, 0});
    contents.files.push_back(std::string("rgb/") + name);
  }
  writeFramesCsv(partial / "rgb" / "frames.csv", frames);
  contents.files.push_back("rgb/frames.csv");

  std::vector<double> line_times;
  EnviWriter cube(partial / "uhi" / "cube.hdr", sampleCubeHeader());
  for (int j = 0; j < kLines; ++j) {
    const double t = kStartTime + j / kLineRate;
    line_times.push_back(t);
    cube.writeLine(renderScanLine(texture, t).data());
  }
  cube.finish();
  contents.files.push_back("uhi/cube.hdr");
  contents.files.push_back("uhi/cube.raw");
  writeLinesCsv(partial / "uhi" / "lines.csv", line_times);
  contents.files.push_back("uhi/lines.csv");

  const InsTable ins = sampleIns();
  writeInsCsv(partial / "nav" / "ins.csv", ins);
  contents.files.push_back("nav/ins.csv");

  std::filesystem::remove_all(target);
  std::filesystem::rename(partial, target);

  contents.rgb_frames = kFrames;
  contents.rgb_width = kWidth;
  contents.rgb_height = kHeight;
  contents.uhi_lines = kLines;
  contents.uhi_samples = kSamples;
  contents.uhi_bands = kBands;
  contents.ins_fixes = kInsFixes;
  contents.duration_s = std::max((kFrames - 1) / kFrameRate, (kLines - 1) / kLineRate);
  return contents;
}

}  // namespace hsmap
