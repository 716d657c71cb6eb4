// StrictYamlMap::maps: a list of maps (e.g. survey.yaml's lights.lamps), each
// element read as strictly as a map and named "<key>[i]" at its own line.
#include <gtest/gtest.h>

#include <string>

#include "core/survey/strict_yaml_map.h"
#include "tests/support/expect_input_error.h"

namespace hsmap {
namespace {

using testing::expectInputError;

// `text` read as the root map of "f.yaml" with the one key `lights`.
StrictYamlMap lights(const std::string& text) {
  const StrictYamlMap root(
      "f.yaml", parseYamlText(text, "f.yaml"), "", 1, {"lights"});
  return root.map("lights", {"lamps"});
}

TEST(StrictYamlMapListTest, ReadsBlockAndFlowElementsWithTheirDottedKeysAndLines) {
  const StrictYamlMap map = lights(
      "lights:\n"                              // 1
      "  lamps:\n"                             // 2
      "    - position_m: [1, 2, 3]\n"          // 3
      "      axis: [0, 0, 1]\n"                // 4
      "    - {position_m: [4, 5, 6]}\n");      // 5
  const std::vector<StrictYamlMap> lamps = map.maps("lamps", {"position_m", "axis"});
  ASSERT_EQ(lamps.size(), 2u);
  EXPECT_EQ(lamps[0].dottedKey(), "lights.lamps[0]");
  EXPECT_EQ(lamps[1].dottedKey(), "lights.lamps[1]");
  EXPECT_EQ(lamps[0].numbers("position_m", 3), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(lamps[1].numbers("position_m", 3), (std::vector<double>{4, 5, 6}));
  EXPECT_TRUE(lamps[0].has("axis"));
  EXPECT_FALSE(lamps[1].has("axis"));
  EXPECT_EQ(lamps[0].lineOf("axis"), 4);
  EXPECT_EQ(lamps[1].where("axis"), "line 5, key lights.lamps[1].axis");
}

TEST(StrictYamlMapListTest, AnEmptyListIsReturnedForTheCallerToJudge) {
  EXPECT_TRUE(lights("lights:\n  lamps: []\n").maps("lamps", {"axis"}).empty());
}

TEST(StrictYamlMapListTest, ErrorsNameTheElementItsLineAndWhatWasExpected) {
  expectInputError(
      [] { lights("lights:\n  lamps: 3\n").maps("lamps", {"position_m", "axis"}); }, "f.yaml",
      "line 2, key lights.lamps: expected a list of maps with keys (position_m, axis), got '3'");
  expectInputError(
      [] { lights("lights:\n  lamps:\n").maps("lamps", {"position_m", "axis"}); }, "f.yaml",
      "line 2, key lights.lamps: expected a list of maps with keys (position_m, axis), got "
      "nothing");
  expectInputError([] { lights("lights:\n  lamps: {axis: 1}\n").maps("lamps", {"axis"}); },
                   "f.yaml",
                   "line 2, key lights.lamps: expected a list of maps with keys (axis), got a map");
  expectInputError([] { lights("lights: {}\n").maps("lamps", {"axis"}); }, "f.yaml",
                   "line 1, key lights.lamps: missing required key");
  expectInputError(
      [] {
        lights("lights:\n  lamps:\n    - {axis: [0, 0, 1]}\n    - 7\n")
            .maps("lamps", {"position_m", "axis"});
      },
      "f.yaml",
      "line 4, key lights.lamps[1]: expected a map with keys (position_m, axis), got '7'");
  expectInputError(
      [] {
        lights("lights:\n  lamps:\n    - axis: [0, 0, 1]\n      colour: red\n")
            .maps("lamps", {"position_m", "axis"});
      },
      "f.yaml", "line 4, key lights.lamps[0].colour: unknown key; expected one of: position_m, axis");
  expectInputError(
      [] {
        lights("lights:\n  lamps:\n    - {axis: 1}\n    - {axis: 2, axis: 3}\n")
            .maps("lamps", {"axis"});
      },
      "f.yaml", "line 4, key lights.lamps[1].axis: duplicated key (first given at line 4)");
  // A value inside an element is reported at the element's dotted key.
  expectInputError(
      [] {
        const auto lamps = lights("lights:\n  lamps:\n    - {axis: [0, x, 1]}\n")
                               .maps("lamps", {"axis"});
        lamps[0].numbers("axis", 3);
      },
      "f.yaml", "line 3, key lights.lamps[0].axis[1]: expected a number, got 'x'");
}

}  // namespace
}  // namespace hsmap
