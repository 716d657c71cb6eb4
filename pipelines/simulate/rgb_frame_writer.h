#pragma once
// RgbFrameWriter: writes the simulated RGB frames in the survey format's
// forms (docs/SURVEY_FORMAT.md), chosen by rgb.encoding.format:
//   png   rgb/frame_NNNNNN.png listed in rgb/frames.csv: lossless, 8-bit (the
//         default; Huffman-only deflate, fast and small on noisy images);
//   jpeg  rgb/frame_NNNNNN.jpg listed in rgb/frames.csv, at jpeg_quality
//         (libjpeg's 1-100 scale, 4:2:0 chroma as OpenCV writes it);
//   h264  one video, rgb/video.mp4, that survey.yaml names as rgb.video with
//         start_time and fps (frame i at start_time + i / fps). Encoded by
//         OpenCV's VideoWriter through its FFmpeg backend ('avc1' in MP4:
//         libx264, YUV 4:2:0). OpenCV (4.6 here) does not expose the encoder's
//         bit rate or quality for H.264: its FFmpeg backend sets libx264 to
//         constant quality, CRF 23, with x264's default preset and key-frame
//         interval, so the bit rate follows the content (noise, texture,
//         motion); finish() reports the one obtained.
// Images and still-image files are written in parallel (TBB); video frames in
// order. Same frames, same bytes (x264 is deterministic by default).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace cv {
class VideoWriter;
}

namespace hsmap {

enum class RgbFrameFormat { png, jpeg, h264 };

struct RgbEncodingConfig {
  RgbFrameFormat format = RgbFrameFormat::png;
  int jpeg_quality = 95;  // jpeg only, in [1, 100]
};

const char* rgbFrameFormatName(RgbFrameFormat format);

class RgbFrameWriter {
 public:
  // Writes into `rgb_folder` (the survey's rgb/); frames of `size` at `rate_hz`.
  RgbFrameWriter(const std::filesystem::path& rgb_folder, const RgbEncodingConfig& config,
                 cv::Size size, double rate_hz);
  ~RgbFrameWriter();

  bool isVideo() const { return config_.format == RgbFrameFormat::h264; }
  // The video file relative to the survey folder ("rgb/video.mp4"), for survey.yaml.
  static std::filesystem::path videoPath() { return "rgb/video.mp4"; }
  // The image file of frame k, relative to rgb/ (empty for a video).
  std::string frameFile(std::int64_t k) const;
  // Writes frames first_index .. first_index + images.size() - 1, in order
  // across calls. Throws std::runtime_error when a file cannot be written.
  void write(std::int64_t first_index, const std::vector<cv::Mat>& images);
  // Closes the video; the bytes written by all frames.
  std::uintmax_t finish();

 private:
  std::filesystem::path folder_;
  RgbEncodingConfig config_;
  std::unique_ptr<cv::VideoWriter> video_;
  std::uintmax_t bytes_ = 0;
  std::int64_t written_ = 0;
};

}  // namespace hsmap
