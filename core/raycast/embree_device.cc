#include "core/raycast/embree_device.h"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

namespace hsmap {

namespace {

// Trivially constructible types only: no dynamic thread-local initialisation,
// so reading them costs no guard check.
thread_local RTCError pending_code = RTC_ERROR_NONE;
thread_local char pending_message[256];

void recordError(void* /*user*/, RTCError code, const char* message) {
  if (pending_code != RTC_ERROR_NONE) return;  // keep the first error
  pending_code = code;
  std::snprintf(pending_message, sizeof(pending_message), "%s", message != nullptr ? message : "");
}

}  // namespace

const char* embreeErrorName(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN:
      return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION:
      return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "RTC_ERROR_UNSUPPORTED_CPU";
    case RTC_ERROR_CANCELLED:
      return "RTC_ERROR_CANCELLED";
  }
  return "RTC_ERROR_(unrecognised code)";
}

void throwIfEmbreeError(const char* call) {
  if (pending_code == RTC_ERROR_NONE) [[likely]]
    return;
  const std::string what = std::string("Embree error in ") + call + ": " +
                           embreeErrorName(pending_code) + ": " + pending_message;
  pending_code = RTC_ERROR_NONE;
  pending_message[0] = '\0';
  throw std::runtime_error(what);
}

EmbreeDevice::EmbreeDevice(const char* config) {
  device_ = rtcNewDevice(config);
  if (device_ == nullptr) {
    // A device that failed to be created has no callback yet; Embree keeps
    // the creation error for the null device.
    throw std::runtime_error(std::string("Embree error in rtcNewDevice: ") +
                             embreeErrorName(rtcGetDeviceError(nullptr)) +
                             ": could not create a device with configuration '" + config + "'");
  }
  rtcSetDeviceErrorFunction(device_, recordError, nullptr);
}

EmbreeDevice::~EmbreeDevice() {
  if (device_ != nullptr) rtcReleaseDevice(device_);
}

EmbreeDevice::EmbreeDevice(EmbreeDevice&& other) noexcept
    : device_(std::exchange(other.device_, nullptr)) {}

EmbreeDevice& EmbreeDevice::operator=(EmbreeDevice&& other) noexcept {
  if (this != &other) {
    if (device_ != nullptr) rtcReleaseDevice(device_);
    device_ = std::exchange(other.device_, nullptr);
  }
  return *this;
}

}  // namespace hsmap
