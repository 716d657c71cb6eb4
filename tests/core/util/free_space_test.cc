#include "core/util/free_space.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

namespace hsmap {
namespace {

TEST(FreeSpace, ASmallWriteFitsAndAnImpossibleOneSaysWhatWhereAndHowMuch) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path();
  EXPECT_NO_THROW(requireFreeSpace(folder, 1, "a byte"));
  try {
    requireFreeSpace(folder, std::numeric_limits<std::uint64_t>::max(), "the ortho-image (smaller: --ortho-pixel)");
    FAIL() << "no error for an impossible size";
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind("the ortho-image (smaller: --ortho-pixel) needs 18446744073.7 GB in " +
                                folder.string() + ", which has ",
                            0),
              0u)
        << message;
    EXPECT_NE(message.find(" GB free"), std::string::npos) << message;
  }
}

TEST(FreeSpace, AMissingFolderIsAnError) {
  EXPECT_THROW(requireFreeSpace("/nonexistent/hsmap/folder", 1, "x"), std::filesystem::filesystem_error);
}

}  // namespace
}  // namespace hsmap
