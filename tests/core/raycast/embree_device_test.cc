#include "core/raycast/embree_device.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <utility>

namespace hsmap {
namespace {

std::string errorOf(const char* call) {
  try {
    throwIfEmbreeError(call);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(EmbreeDevice, ReportedErrorsBecomeExceptionsOnce) {
  const EmbreeDevice device;
  RTCScene scene = rtcNewScene(device.get());
  ASSERT_NE(scene, nullptr);
  EXPECT_EQ(errorOf("rtcNewScene"), "");
  // REFIT is a geometry build quality, not a scene one: Embree reports an error.
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_REFIT);
  EXPECT_EQ(errorOf("rtcSetSceneBuildQuality"),
            "Embree error in rtcSetSceneBuildQuality: RTC_ERROR_UNKNOWN: invalid build quality");
  // The record is cleared by the check.
  EXPECT_EQ(errorOf("rtcSetSceneBuildQuality"), "");
  rtcReleaseScene(scene);
}

TEST(EmbreeDevice, BadConfigurationThrowsFromTheConstructor) {
  try {
    EmbreeDevice device("threads=abc,foo");
    ADD_FAILURE() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              "Embree error in rtcNewDevice: RTC_ERROR_UNKNOWN: could not create a device with "
              "configuration 'threads=abc,foo'");
  }
  // The failure leaves nothing pending for later checks on this thread.
  EXPECT_EQ(errorOf("rtcNewDevice"), "");
}

TEST(EmbreeDevice, MovesOwnership) {
  EmbreeDevice first;
  const RTCDevice handle = first.get();
  EmbreeDevice second(std::move(first));
  EXPECT_EQ(first.get(), nullptr);
  EXPECT_EQ(second.get(), handle);
  EmbreeDevice third;
  third = std::move(second);
  EXPECT_EQ(third.get(), handle);
}

TEST(EmbreeDevice, NamesErrorCodes) {
  EXPECT_STREQ(embreeErrorName(RTC_ERROR_INVALID_ARGUMENT), "RTC_ERROR_INVALID_ARGUMENT");
  EXPECT_STREQ(embreeErrorName(RTC_ERROR_OUT_OF_MEMORY), "RTC_ERROR_OUT_OF_MEMORY");
}

}  // namespace
}  // namespace hsmap
