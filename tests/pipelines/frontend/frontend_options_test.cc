#include "pipelines/frontend/frontend_options.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hsmap {
namespace {

TEST(FrontendOptions, DefaultsAreValid) { EXPECT_NO_THROW(FrontendOptions{}.validate()); }

TEST(FrontendOptions, ValidateNamesTheBadField) {
  FrontendOptions options;
  options.keyframe_parallax_deg = 0.0;
  try {
    options.validate();
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("keyframe_parallax_deg"), std::string::npos) << error.what();
  }
  options = FrontendOptions{};
  options.last_frame = 3;
  options.first_frame = 5;
  EXPECT_THROW(options.validate(), std::invalid_argument);
  options = FrontendOptions{};
  options.init_min_cheirality_fraction = 1.5;
  EXPECT_THROW(options.validate(), std::invalid_argument);
}

TEST(FrontendOptions, PixelSizesScaleWithTheImageAndErrorThresholdsNeverShrink) {
  const FrontendOptions options;
  EXPECT_DOUBLE_EQ(options.sizeScale(1920), 2.0);
  EXPECT_DOUBLE_EQ(options.sizeScale(320), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(options.errorScale(1920), 2.0);
  EXPECT_DOUBLE_EQ(options.errorScale(320), 1.0);
}

}  // namespace
}  // namespace hsmap
