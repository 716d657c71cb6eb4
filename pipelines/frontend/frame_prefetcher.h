#pragma once
// FramePrefetcher: decodes and pre-processes the survey's frames on a second
// thread, ahead of tracking, through a bounded queue.
//
// PNG/JPEG decoding costs about as much as tracking a frame; on two cores
// the two overlap. The queue holds at most `capacity` frames (a 960x540 grey
// image is 0.5 MB), so memory does not grow with the survey. Frames come out
// in order. A frame that cannot be decoded (RgbFrameSource throws
// InputError) comes out with `error` set, never silently dropped; any other
// exception stops the prefetcher and is rethrown by next().
//
// The RgbFrameSource is used by the prefetch thread only while it runs.

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <opencv2/core.hpp>

#include "core/survey/rgb_frame_source.h"
#include "pipelines/frontend/frontend_options.h"
#include "pipelines/frontend/image_preprocessor.h"

namespace hsmap {

struct PrefetchedFrame {
  int index = 0;
  double t = 0.0;
  cv::Mat gray;          // pre-processed (ImagePreprocessor); empty when undecodable
  cv::Mat linear;        // before CLAHE (ImagePreprocessor::process), with compensate_gain only
  cv::Mat saturated;     // its pixels saturated in the camera, with compensate_gain only
  ImageQuality quality;
  std::string error;     // the decoder's message (file named) when undecodable
  double decode_ms = 0.0;
  double preprocess_ms = 0.0;
};

class FramePrefetcher {
 public:
  // Frames first..last (inclusive) of `source`.
  // `lamp_light_field`: see ImagePreprocessor (empty: none).
  FramePrefetcher(const RgbFrameSource& source, const FrontendOptions& options, int width_px,
                  int height_px, int first, int last, cv::Mat lamp_light_field = {});
  ~FramePrefetcher();
  FramePrefetcher(const FramePrefetcher&) = delete;
  FramePrefetcher& operator=(const FramePrefetcher&) = delete;

  // The next frame in order; std::nullopt after the last.
  std::optional<PrefetchedFrame> next();

 private:
  void run();

  const RgbFrameSource& source_;
  ImagePreprocessor preprocessor_;
  int first_, last_;
  std::size_t capacity_;
  bool keep_linear_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<PrefetchedFrame> queue_;
  bool done_ = false;
  bool stop_ = false;
  std::exception_ptr failure_;
  std::thread thread_;
};

}  // namespace hsmap
