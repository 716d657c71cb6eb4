#pragma once
// TeeStream: an output stream that writes everything to two streams at
// once, e.g. the terminal and the run's log file (`hsmap run --log FILE`).

#include <ostream>
#include <algorithm>
#include <streambuf>

namespace hsmap {

class TeeBuffer : public std::streambuf {
 public:
  TeeBuffer(std::streambuf* first, std::streambuf* second) : first_(first), second_(second) {}

 protected:
  int overflow(int c) override {
    if (c == traits_type::eof()) return traits_type::not_eof(c);
    const bool ok = first_->sputc(char(c)) != traits_type::eof() && second_->sputc(char(c)) != traits_type::eof();
    return ok ? c : traits_type::eof();
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    const std::streamsize a = first_->sputn(s, n);
    const std::streamsize b = second_->sputn(s, n);
    return std::min(a, b);
  }
  int sync() override {
    const int a = first_->pubsync();
    const int b = second_->pubsync();
    return a == 0 && b == 0 ? 0 : -1;
  }

 private:
  std::streambuf* first_;
  std::streambuf* second_;
};

class TeeStream : public std::ostream {
 public:
  TeeStream(std::ostream& first, std::ostream& second)
      : std::ostream(nullptr), buffer_(first.rdbuf(), second.rdbuf()) {
    rdbuf(&buffer_);
  }

 private:
  TeeBuffer buffer_;
};

}  // namespace hsmap
