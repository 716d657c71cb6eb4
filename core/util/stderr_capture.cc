#include "core/util/stderr_capture.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace hsmap {

StderrCapture::StderrCapture() {
  std::fflush(stderr);
  char name[] = "/tmp/hsmap-stderr-XXXXXX";
  capture_fd_ = ::mkstemp(name);
  if (capture_fd_ < 0) return;  // no capture: library output stays visible, nothing breaks
  ::unlink(name);
  saved_fd_ = ::dup(STDERR_FILENO);
  if (saved_fd_ < 0 || ::dup2(capture_fd_, STDERR_FILENO) < 0) {
    if (saved_fd_ >= 0) ::close(saved_fd_);
    ::close(capture_fd_);
    saved_fd_ = capture_fd_ = -1;
  }
}

StderrCapture::~StderrCapture() {
  if (saved_fd_ >= 0) {
    std::fflush(stderr);
    ::dup2(saved_fd_, STDERR_FILENO);
    ::close(saved_fd_);
  }
  if (capture_fd_ >= 0) ::close(capture_fd_);
}

std::string StderrCapture::text() const {
  if (capture_fd_ < 0) return {};
  std::fflush(stderr);
  std::string text(64 * 1024, '\0');
  const ssize_t got = ::pread(capture_fd_, text.data(), text.size(), 0);
  text.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
  return text;
}

std::string StderrCapture::firstLine() const {
  const std::string all = text();
  std::string_view rest = all;
  while (!rest.empty()) {
    const std::size_t end = rest.find('\n');
    std::string_view line = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
    while (!line.empty() && line.front() == ' ') line.remove_prefix(1);
    for (const std::string_view prefix : {"libpng error: ", "libpng warning: "}) {
      if (line.substr(0, prefix.size()) == prefix) line.remove_prefix(prefix.size());
    }
    if (!line.empty()) return std::string(line);
  }
  return {};
}

}  // namespace hsmap
