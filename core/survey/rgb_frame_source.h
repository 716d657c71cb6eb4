#pragma once
// RgbFrameSource: the survey's RGB frames, from an image list (frames.csv) or
// from a video file, behind one interface: frameCount(), time(i), frame(i).
//
// Image list: the rows of frames.csv (file,t); image paths are relative to the
// folder that holds frames.csv (rgb/ in the standard layout). Every listed
// file must be a regular file with a valid PNG or JPEG header when the source
// is opened (core/io/image_header.h: signature and pixel size, read without
// decoding) — a missing, empty, foreign or damaged file is reported with
// frames.csv's line — but images are decoded only when asked for, so
// opening a long survey stays cheap (~1 ms per 100 frames).
//
// Video: opened with cv::VideoCapture's FFmpeg backend (it must open); frame i has time
// start_time + i / fps. The frame count is the container's
// CAP_PROP_FRAME_COUNT (it must be > 0); a frame that the decoder then cannot
// produce is reported by frame(i) as InputError naming the video.
//
// frame(i) returns an 8-bit, 3-channel BGR image (OpenCV's order). What the
// decoding libraries print (libpng, FFmpeg) is captured (stderr_capture.h)
// and folded into the InputError, so the user sees one line. The source is
// not thread-safe: a video source keeps its decoder position.

#include <filesystem>
#include <memory>
#include <optional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/survey/csv_table.h"

namespace cv {
class VideoCapture;
}

namespace hsmap {

class RgbFrameSource {
 public:
  // Reads and validates frames.csv (csv_table.h) and checks that every image exists.
  static RgbFrameSource fromFrameList(const std::filesystem::path& frames_csv);
  // Opens `video`; throws InputError if OpenCV cannot open it or reports no frames.
  static RgbFrameSource fromVideo(const std::filesystem::path& video, double start_time,
                                  double fps);

  // An empty source (no frames), e.g. a member before loading.
  RgbFrameSource();
  RgbFrameSource(RgbFrameSource&&) noexcept;
  RgbFrameSource& operator=(RgbFrameSource&&) noexcept;
  ~RgbFrameSource();

  bool isVideo() const { return is_video_; }
  // frames.csv or the video file.
  const std::filesystem::path& sourcePath() const { return source_path_; }
  int frameCount() const { return static_cast<int>(times_.size()); }
  double time(int i) const { return times_.at(static_cast<std::size_t>(i)); }
  const std::vector<double>& times() const { return times_; }
  // The image file of frame i (image lists only; empty for a video).
  std::filesystem::path framePath(int i) const;
  // Decodes frame i; throws InputError naming the image (or video) file when
  // it cannot be decoded, and std::out_of_range for a bad index.
  cv::Mat frame(int i) const;
  // Width and height of the first frame, from its header (a video reports its
  // stream size); frameSize(i) of frame i.
  cv::Size frameSize() const;
  cv::Size frameSize(int i) const;
  // The first frame whose size differs from `size`, if any.
  std::optional<int> findFrameOfOtherSize(cv::Size size) const;
  // The 1-based line of frame i in frames.csv (0 for a video).
  long long frameLine(int i) const;

 private:
  bool is_video_ = false;
  std::filesystem::path source_path_;
  std::vector<double> times_;
  std::vector<FrameRow> rows_;  // image lists
  std::vector<std::filesystem::path> image_paths_;
  std::vector<cv::Size> sizes_;  // from each image's header
  std::unique_ptr<cv::VideoCapture> video_;  // videos
  cv::Size video_size_;
  mutable int next_video_frame_ = 0;
};

}  // namespace hsmap
