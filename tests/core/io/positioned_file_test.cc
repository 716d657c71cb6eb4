#include "core/io/positioned_file.h"

#include <string>

#include <gtest/gtest.h>

#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

TEST(PositionedFile, ReadsAtOffsets) {
  TempFolder dir;
  const PositionedFile file(dir.write("a.bin", "0123456789"), PositionedFile::Access::sequential);
  EXPECT_EQ(file.size(), 10u);
  std::byte out[4];
  file.readAt(3, out, 4);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(out), 4), "3456");
  file.readAt(0, out, 1);
  EXPECT_EQ(static_cast<char>(out[0]), '0');
}

TEST(PositionedFile, ErrorsNameTheFileAndWhere) {
  TempFolder dir;
  const auto path = dir.write("short.bin", "abc");
  const PositionedFile file(path);
  std::byte out[8];
  try {
    file.readAt(1, out, 5);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), path.string() + ":byte 3: file ended early: expected 3 more bytes");
  }
  try {
    PositionedFile missing(dir / "absent.bin");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), (dir / "absent.bin").string() + ": file not found");
  }
  EXPECT_THROW(PositionedFile{dir.path()}, InputError);
}

}  // namespace
}  // namespace hsmap
