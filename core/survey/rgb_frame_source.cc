#include "core/survey/rgb_frame_source.h"

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <stdexcept>

#include "core/survey/number_text.h"
#include "core/io/image_header.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"
#include "core/util/regular_file.h"
#include "core/util/stderr_capture.h"

namespace hsmap {
namespace {

// ": <what the library said>", escaped and shortened, or nothing.
std::string libraryDetail(const StderrCapture& capture) {
  const std::string line = capture.firstLine();
  return line.empty() ? std::string() : ": " + escapeForMessage(line, 120);
}

}  // namespace

RgbFrameSource::RgbFrameSource() = default;
RgbFrameSource::RgbFrameSource(RgbFrameSource&&) noexcept = default;
RgbFrameSource& RgbFrameSource::operator=(RgbFrameSource&&) noexcept = default;
RgbFrameSource::~RgbFrameSource() = default;

RgbFrameSource RgbFrameSource::fromFrameList(const std::filesystem::path& frames_csv) {
  RgbFrameSource source;
  source.source_path_ = frames_csv;
  source.rows_ = readFramesCsv(frames_csv);
  const std::filesystem::path folder = frames_csv.parent_path();
  source.times_.reserve(source.rows_.size());
  source.image_paths_.reserve(source.rows_.size());
  source.sizes_.reserve(source.rows_.size());
  for (const auto& row : source.rows_) {
    const std::filesystem::path image = folder / row.file;
    const auto fail = [&](const std::string& detail) {
      throw InputError(frames_csv, InputError::atLine(row.line_number),
                       "column 'file': image " + quoteForMessage(row.file) + " " + detail);
    };
    if (const auto why = whyNotRegularFile(image)) {
      if (*why == "not found") fail("not found (expected the file " + image.string() + ")");
      fail("is " + *why + "; expected a PNG or JPEG image file (" + image.string() + ")");
    }
    // Every frame's header, not just the first: a damaged or foreign file
    // among 1,200 frames must stop validation, not a stage hours later.
    std::string why;
    const auto header = readImageHeader(image, &why);
    if (!header) fail("is " + why + " (" + image.string() + ")");
    source.times_.push_back(row.t);
    source.image_paths_.push_back(image);
    source.sizes_.emplace_back(header->width, header->height);
  }
  return source;
}

RgbFrameSource RgbFrameSource::fromVideo(const std::filesystem::path& video, double start_time,
                                         double fps) {
  if (!std::isfinite(start_time) || !(fps > 0.0) || !std::isfinite(fps)) {
    throw std::invalid_argument("RgbFrameSource::fromVideo: bad start_time or fps");
  }
  std::error_code error;
  if (!std::filesystem::is_regular_file(video, error)) {
    throw InputError(video, "", "video file not found");
  }
  RgbFrameSource source;
  source.is_video_ = true;
  source.source_path_ = video;
  double count = 0.0;
  {
    // FFmpeg only: the GStreamer backend prints its own warnings and, on a
    // file it cannot play, may wait on its pipeline. The capture keeps
    // FFmpeg's messages for hsmap's error line.
    const StderrCapture library_output;
    source.video_ = std::make_unique<cv::VideoCapture>(video.string(), cv::CAP_FFMPEG);
    if (!source.video_->isOpened()) {
      throw InputError(video, "",
                       "cannot open the video (unsupported container or codec?)" +
                           libraryDetail(library_output));
    }
    count = source.video_->get(cv::CAP_PROP_FRAME_COUNT);
    source.video_size_ = {static_cast<int>(source.video_->get(cv::CAP_PROP_FRAME_WIDTH)),
                          static_cast<int>(source.video_->get(cv::CAP_PROP_FRAME_HEIGHT))};
  }
  if (!(count >= 1.0)) {
    throw InputError(video, "",
                     "the video reports no frames (frame count " + formatDouble(count) + ")");
  }
  const auto frames = static_cast<std::size_t>(std::llround(count));
  source.times_.reserve(frames);
  for (std::size_t i = 0; i < frames; ++i) {
    source.times_.push_back(start_time + static_cast<double>(i) / fps);
  }
  return source;
}

std::filesystem::path RgbFrameSource::framePath(int i) const {
  if (is_video_) return {};
  return image_paths_.at(static_cast<std::size_t>(i));
}

cv::Mat RgbFrameSource::frame(int i) const {
  if (i < 0 || i >= frameCount()) {
    throw std::out_of_range("RgbFrameSource::frame: index " + std::to_string(i) + " of " +
                            std::to_string(frameCount()));
  }
  cv::Mat image;
  if (!is_video_) {
    const auto index = static_cast<std::size_t>(i);
    const StderrCapture library_output;
    image = cv::imread(image_paths_[index].string(), cv::IMREAD_COLOR);
    if (image.empty()) {
      throw InputError(image_paths_[index], "",
                       "cannot decode the image (listed at " + source_path_.string() + ":" +
                           InputError::atLine(rows_[index].line_number) + ")" +
                           libraryDetail(library_output));
    }
    return image;
  }
  // Seeking is slow and not frame-exact in every container, so sequential
  // reads continue from the decoder's position.
  const StderrCapture library_output;
  if (i != next_video_frame_) video_->set(cv::CAP_PROP_POS_FRAMES, static_cast<double>(i));
  if (!video_->read(image) || image.empty()) {
    next_video_frame_ = -1;  // position unknown: seek next time
    throw InputError(source_path_, "frame " + std::to_string(i),
                     "cannot decode the frame (the video has " + std::to_string(frameCount()) +
                         " frames by its header)" + libraryDetail(library_output));
  }
  next_video_frame_ = i + 1;
  return image;
}

cv::Size RgbFrameSource::frameSize() const {
  if (is_video_) return video_size_;
  return sizes_.empty() ? cv::Size() : sizes_.front();
}

std::optional<int> RgbFrameSource::findFrameOfOtherSize(cv::Size size) const {
  if (is_video_) return video_size_ == size ? std::nullopt : std::optional<int>(0);
  for (std::size_t i = 0; i < sizes_.size(); ++i) {
    if (sizes_[i] != size) return static_cast<int>(i);
  }
  return std::nullopt;
}

cv::Size RgbFrameSource::frameSize(int i) const {
  if (is_video_) return video_size_;
  return sizes_.at(static_cast<std::size_t>(i));
}

long long RgbFrameSource::frameLine(int i) const {
  if (is_video_) return 0;
  return rows_.at(static_cast<std::size_t>(i)).line_number;
}

}  // namespace hsmap
