#pragma once
// EmbreeDevice: owns one Embree 3 device and turns the errors Embree reports
// into C++ exceptions.
//
// Embree reports errors through a C callback, from inside its API functions.
// Throwing from that callback would unwind through Embree's own code, so the
// callback only records the error (code and message, per thread: Embree
// calls it on the thread that made the failing call) and callers check with
// throwIfEmbreeError() right after each Embree call. The record is plain
// thread-local data, so the check is a thread-local load and cheap enough to
// make after every ray query.
//
// A device that cannot be created (bad configuration string, unsupported CPU)
// throws std::runtime_error from the constructor. Errors are reported as
//   std::runtime_error("Embree error in <call>: <CODE NAME>: <Embree's message>").

#include <embree3/rtcore.h>

namespace hsmap {

class EmbreeDevice {
 public:
  // `config` is Embree's device configuration string ("" for defaults; see
  // rtcNewDevice). Embree's verbose output stays off unless `config` asks.
  explicit EmbreeDevice(const char* config = "");
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;
  EmbreeDevice(EmbreeDevice&& other) noexcept;
  EmbreeDevice& operator=(EmbreeDevice&& other) noexcept;

  RTCDevice get() const { return device_; }

 private:
  RTCDevice device_ = nullptr;
};

// Name of an Embree error code, e.g. "RTC_ERROR_INVALID_ARGUMENT".
const char* embreeErrorName(RTCError code);

// Throws std::runtime_error if an Embree call on this thread reported an error
// since the last check (the first error wins), and clears the record.
void throwIfEmbreeError(const char* call);

}  // namespace hsmap
