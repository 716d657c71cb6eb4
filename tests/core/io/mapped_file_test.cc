#include "core/io/mapped_file.h"

#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

long rssFileKilobytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("RssFile:", 0) == 0) return std::stol(line.substr(8));
  }
  return -1;
}

TEST(MappedFile, MapsTheContent) {
  TempFolder dir;
  const auto path = dir.write("a.bin", std::string("hello\0world", 11));
  const MappedFile map(path);
  ASSERT_EQ(map.size(), 11u);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(map.data()), map.size()), std::string("hello\0world", 11));
  MappedFile moved = MappedFile(path, MappedFile::Access::sequential);
  EXPECT_EQ(moved.size(), 11u);
  EXPECT_EQ(static_cast<char>(moved.data()[6]), 'w');
}

TEST(MappedFile, EmptyFileMapsToNothing) {
  TempFolder dir;
  const MappedFile map(dir.write("empty.bin", ""));
  EXPECT_EQ(map.size(), 0u);
  EXPECT_EQ(map.data(), nullptr);
  map.release(0, 10);  // harmless
}

TEST(MappedFile, ErrorsNameTheFile) {
  TempFolder dir;
  try {
    MappedFile map(dir / "absent.raw");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), (dir / "absent.raw").string() + ": file not found");
  }
  try {
    MappedFile map(dir.path());
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), dir.path().string() + ": is a directory; expected a regular file");
  }
}

// Release drops the pages from the process but not from the file: reading
// again gives the same bytes.
TEST(MappedFile, ReleaseShrinksTheResidentSetAndKeepsTheContent) {
  TempFolder dir;
  constexpr std::size_t kBytes = 32u << 20;
  {
    std::vector<char> data(kBytes);
    for (std::size_t i = 0; i < kBytes; ++i) data[i] = static_cast<char>(i * 7 + i / 4096);
    std::ofstream out(dir / "big.bin", std::ios::binary);
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
  }
  const MappedFile map(dir / "big.bin");
  const long before = rssFileKilobytes();
  ASSERT_GE(before, 0);
  unsigned sum = 0;
  for (std::size_t i = 0; i < kBytes; i += 4096) sum += static_cast<unsigned char>(map.data()[i]);
  const long touched = rssFileKilobytes();
  EXPECT_GT(touched - before, 28 * 1024) << "touching 32 MB should map ~32 MB";
  map.release(0, kBytes);
  const long released = rssFileKilobytes();
  EXPECT_LT(released - before, 4 * 1024) << "release should unmap the pages";
  unsigned again = 0;
  for (std::size_t i = 0; i < kBytes; i += 4096) again += static_cast<unsigned char>(map.data()[i]);
  EXPECT_EQ(again, sum);
  EXPECT_EQ(static_cast<char>(map.data()[12345]), static_cast<char>(12345 * 7 + 12345 / 4096));
}

// Partial pages at the ends of the range stay mapped (their other bytes may
// still be in use); only whole pages go.
TEST(MappedFile, ReleaseKeepsPartialPages) {
  TempFolder dir;
  const std::string content(3 * 4096, 'x');
  const MappedFile map(dir.write("pages.bin", content));
  for (std::size_t i = 0; i < content.size(); i += 4096) ASSERT_EQ(static_cast<char>(map.data()[i]), 'x');
  const long before = rssFileKilobytes();
  map.release(1, 4096);  // covers no whole page
  EXPECT_EQ(rssFileKilobytes(), before);
  map.release(1, 2 * 4096);  // covers page 1 only
  EXPECT_EQ(rssFileKilobytes(), before - 4);
}

}  // namespace
}  // namespace hsmap
