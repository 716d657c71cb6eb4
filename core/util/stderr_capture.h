#pragma once
// StderrCapture: keeps what third-party libraries print on stderr while a
// call into them runs, so that the user sees hsmap's one-line error and not
// libpng's "IHDR: CRC error" or a video backend's warnings before it.
//
// libpng, libjpeg and the video backends behind OpenCV write their
// diagnostics straight to file descriptor 2; OpenCV offers no hook for them.
// The capture redirects descriptor 2 to an anonymous temporary file for its
// lifetime and restores it on destruction; text() returns what was written
// meanwhile, which a caller may fold (escaped and shortened) into its own
// error message.
//
// Descriptor 2 is process-wide: do not hold a capture while other threads
// may report on stderr (hsmap decodes frames and opens videos on one thread;
// its own progress and errors are printed outside any capture).

#include <string>

namespace hsmap {

class StderrCapture {
 public:
  StderrCapture();
  ~StderrCapture();
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  // What was written to stderr since construction (at most 64 KiB).
  std::string text() const;
  // The first non-empty line of text(), without library prefixes such as
  // "libpng error: ", trimmed; empty when nothing was written.
  std::string firstLine() const;

 private:
  int saved_fd_ = -1;    // the original stderr, restored on destruction
  int capture_fd_ = -1;  // the temporary file stderr points at meanwhile
};

}  // namespace hsmap
