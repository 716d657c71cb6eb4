#include "core/survey/rgb_frame_source.h"

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <stdexcept>

#include "core/survey/number_text.h"
#include "core/util/input_error.h"

namespace hsmap {

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
  for (const auto& row : source.rows_) {
    const std::filesystem::path image = folder / row.file;
    std::error_code error;
    if (!std::filesystem::is_regular_file(image, error)) {
      throw InputError(frames_csv, InputError::atLine(row.line_number),
                       "column 'file': image '" + row.file + "' not found (expected the file " +
                           image.string() + ")");
    }
    source.times_.push_back(row.t);
    source.image_paths_.push_back(image);
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
  source.video_ = std::make_unique<cv::VideoCapture>(video.string());
  if (!source.video_->isOpened()) {
    throw InputError(video, "", "OpenCV cannot open the video (unsupported container or codec?)");
  }
  const double count = source.video_->get(cv::CAP_PROP_FRAME_COUNT);
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
    image = cv::imread(image_paths_[index].string(), cv::IMREAD_COLOR);
    if (image.empty()) {
      throw InputError(image_paths_[index], "",
                       "cannot decode the image (listed at " + source_path_.string() + ":" +
                           InputError::atLine(rows_[index].line_number) + ")");
    }
    return image;
  }
  // Seeking is slow and not frame-exact in every container, so sequential
  // reads continue from the decoder's position.
  if (i != next_video_frame_) video_->set(cv::CAP_PROP_POS_FRAMES, static_cast<double>(i));
  if (!video_->read(image) || image.empty()) {
    next_video_frame_ = -1;  // position unknown: seek next time
    throw InputError(source_path_, "frame " + std::to_string(i),
                     "cannot decode the frame (the video has " + std::to_string(frameCount()) +
                         " frames by its header)");
  }
  next_video_frame_ = i + 1;
  return image;
}

cv::Size RgbFrameSource::frameSize() const {
  if (is_video_) {
    return {static_cast<int>(video_->get(cv::CAP_PROP_FRAME_WIDTH)),
            static_cast<int>(video_->get(cv::CAP_PROP_FRAME_HEIGHT))};
  }
  return frame(0).size();
}

}  // namespace hsmap
