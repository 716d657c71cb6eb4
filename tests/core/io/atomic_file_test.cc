#include "core/io/atomic_file.h"

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

TEST(AtomicFile, CommitMovesTheCompleteFileIntoPlace) {
  TempFolder dir;
  const auto target = dir / "product.txt";
  AtomicFile file(target);
  EXPECT_EQ(file.partialPath(), dir / "product.txt.partial");
  file.stream() << "complete";
  EXPECT_FALSE(std::filesystem::exists(target)) << "nothing under the final name before commit";
  file.commit();
  EXPECT_TRUE(file.committed());
  EXPECT_EQ(TempFolder::read(target), "complete");
  EXPECT_FALSE(std::filesystem::exists(file.partialPath()));
  EXPECT_THROW(file.commit(), std::logic_error);
}

TEST(AtomicFile, AbandonedFileLeavesTheOldVersionUntouched) {
  TempFolder dir;
  const auto target = dir.write("product.txt", "old");
  {
    AtomicFile file(target);
    file.stream() << "half-writ";
  }
  EXPECT_EQ(TempFolder::read(target), "old");
  EXPECT_FALSE(std::filesystem::exists(dir / "product.txt.partial"));
  {
    AtomicFile file(target);
    file.stream() << "new";
    file.commit();
  }
  EXPECT_EQ(TempFolder::read(target), "new");
}

TEST(AtomicFile, ByPathForLibrariesThatWriteFiles) {
  TempFolder dir;
  const auto target = dir / "image.png";
  {
    AtomicFile file(target, AtomicFile::Mode::byPath);
    EXPECT_THROW(file.stream(), std::logic_error);
    EXPECT_THROW(file.commit(), std::runtime_error) << "the library wrote nothing";
  }
  AtomicFile file(target, AtomicFile::Mode::byPath);
  std::ofstream(file.partialPath()) << "pixels";
  file.commit();
  EXPECT_EQ(TempFolder::read(target), "pixels");
}

TEST(AtomicFile, MovedFromFileDoesNotRemoveAnything) {
  TempFolder dir;
  AtomicFile first(dir / "a.txt");
  first.stream() << "a";
  AtomicFile second = std::move(first);
  second.commit();
  EXPECT_EQ(TempFolder::read(dir / "a.txt"), "a");
}

TEST(AtomicFile, UnwritableFolderThrows) {
  TempFolder dir;
  EXPECT_THROW(AtomicFile(dir / "missing" / "folder" / "x.txt"), std::runtime_error);
}

}  // namespace
}  // namespace hsmap
