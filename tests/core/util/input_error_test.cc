#include "core/util/input_error.h"

#include <gtest/gtest.h>

namespace hsmap {
namespace {

TEST(InputError, MessageNamesFileLineAndExpectation) {
  const InputError error("nav/ins.csv", InputError::atLine(12),
                         "column 'lat': expected a number, got 'abc'");
  EXPECT_STREQ(error.what(), "nav/ins.csv:line 12: column 'lat': expected a number, got 'abc'");
  EXPECT_EQ(error.file(), "nav/ins.csv");
  EXPECT_EQ(error.where(), "line 12");
}

TEST(InputError, KeyLocationAndWholeFileForm) {
  EXPECT_STREQ(InputError("survey.yaml", InputError::atKey("rgb.camera.fx"), "expected a number").what(),
               "survey.yaml:key rgb.camera.fx: expected a number");
  EXPECT_STREQ(InputError("cube.raw", "", "truncated").what(), "cube.raw: truncated");
}

}  // namespace
}  // namespace hsmap
