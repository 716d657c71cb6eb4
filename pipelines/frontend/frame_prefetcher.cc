#include "pipelines/frontend/frame_prefetcher.h"

#include <chrono>

#include "core/util/input_error.h"

namespace hsmap {

namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

FramePrefetcher::FramePrefetcher(const RgbFrameSource& source, const FrontendOptions& options,
                                 int width_px, int height_px, int first, int last,
                                 cv::Mat lamp_light_field)
    : source_(source),
      preprocessor_(options, width_px, height_px, std::move(lamp_light_field)),
      first_(first),
      last_(last),
      capacity_(std::size_t(options.prefetch_frames)),
      keep_linear_(options.compensate_gain) {
  thread_ = std::thread([this] { run(); });
}

FramePrefetcher::~FramePrefetcher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void FramePrefetcher::run() {
  try {
    for (int i = first_; i <= last_; ++i) {
      PrefetchedFrame frame;
      frame.index = i;
      frame.t = source_.time(i);
      const auto start = std::chrono::steady_clock::now();
      cv::Mat bgr;
      try {
        bgr = source_.frame(i);
      } catch (const InputError& error) {
        frame.error = error.what();
      }
      frame.decode_ms = msSince(start);
      if (frame.error.empty()) {
        const auto start_pre = std::chrono::steady_clock::now();
        frame.gray = preprocessor_.process(bgr, &frame.quality, keep_linear_ ? &frame.linear : nullptr,
                                          keep_linear_ ? &frame.saturated : nullptr);
        frame.preprocess_ms = msSince(start_pre);
      }
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return stop_ || queue_.size() < capacity_; });
      if (stop_) return;
      queue_.push_back(std::move(frame));
      lock.unlock();
      changed_.notify_all();
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    failure_ = std::current_exception();
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  changed_.notify_all();
}

std::optional<PrefetchedFrame> FramePrefetcher::next() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return !queue_.empty() || done_; });
  if (!queue_.empty()) {
    PrefetchedFrame frame = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    changed_.notify_all();
    return frame;
  }
  if (failure_) std::rethrow_exception(failure_);
  return std::nullopt;
}

}  // namespace hsmap
