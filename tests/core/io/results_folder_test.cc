#include "core/io/results_folder.h"

#include <gtest/gtest.h>

#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

TEST(ResultsFolder, CreatesSubFoldersOnDemandAndWritesAtomically) {
  TempFolder dir;
  const ResultsFolder results(dir / "RUN");
  EXPECT_TRUE(std::filesystem::is_directory(dir / "RUN"));
  EXPECT_FALSE(std::filesystem::exists(dir / "RUN" / "trajectory"));
  {
    AtomicFile frames = results.product(results_paths::trajectory_frames);
    frames.stream() << "t,x,y,z,qw,qx,qy,qz\n";
    EXPECT_FALSE(std::filesystem::exists(dir / "RUN" / "trajectory" / "frames.csv"));
    frames.commit();
  }
  EXPECT_EQ(TempFolder::read(dir / "RUN" / "trajectory" / "frames.csv"), "t,x,y,z,qw,qx,qy,qz\n");
  {
    AtomicFile abandoned = results.product(results_paths::metrics_json);
    abandoned.stream() << "{";
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "RUN" / "metrics.json"));
  EXPECT_EQ(results.prepare(results_paths::ortho_hdr), dir / "RUN" / "hyperspectral" / "ortho.hdr");
  EXPECT_TRUE(std::filesystem::is_directory(dir / "RUN" / "hyperspectral"));
}

TEST(ResultsFolder, RejectsPathsOutsideTheFolder) {
  TempFolder dir;
  const ResultsFolder results(dir.path());
  EXPECT_THROW(results.prepare("../escape.txt"), std::invalid_argument);
  EXPECT_THROW(results.prepare("map/../../escape.txt"), std::invalid_argument);
  EXPECT_THROW(results.prepare("/etc/passwd"), std::invalid_argument);
  EXPECT_THROW(results.prepare(""), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
