// --variants (pipelines/compare/variant_list.h): the order kept, and each
// mistake an exact message.

#include "pipelines/compare/variant_list.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hsmap {
namespace {

std::string errorOf(const std::string& text) {
  try {
    parseVariantList(text);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(VariantList, KeepsTheOrderGiven) {
  EXPECT_EQ(parseVariantList("joint,planar"), (std::vector<Variant>{Variant::joint, Variant::planar}));
  EXPECT_EQ(parseVariantList("stacked,planar,sequential,joint"), allCompareVariants());
}

TEST(VariantList, EachMistakeHasItsMessage) {
  EXPECT_EQ(errorOf("planar,fused"),
            "--variants: unknown variant 'fused' in 'planar,fused'; expected names among stacked, planar, "
            "sequential, joint, separated by commas");
  EXPECT_EQ(errorOf("planar, joint"),
            "--variants: unknown variant ' joint' in 'planar, joint'; expected names among stacked, planar, "
            "sequential, joint, separated by commas");
  EXPECT_EQ(errorOf("planar,"),
            "--variants: unknown variant '' in 'planar,'; expected names among stacked, planar, sequential, "
            "joint, separated by commas");
  EXPECT_EQ(errorOf("joint,joint"), "--variants: 'joint' is listed twice in 'joint,joint'");
  EXPECT_EQ(errorOf(""), "--variants: expected at least one variant, got ''");
}

}  // namespace
}  // namespace hsmap
