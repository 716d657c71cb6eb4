#include "core/util/progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

namespace hsmap {
namespace {

TEST(Progress, ReportsCountsPercentAndFinalLine) {
  std::ostringstream out;
  {
    Progress progress("lines", 200, "lines", out, /*min_interval_s=*/1e9);
    progress.advance(50);
    EXPECT_EQ(progress.reportLine().rfind("lines: 50/200 lines (25%)", 0), 0u)
        << progress.reportLine();
    progress.advance(150);
    EXPECT_EQ(out.str(), "") << "no report before the interval elapsed";
  }
  // The destructor prints the final report, once, as its own line (not a terminal).
  const std::string text = out.str();
  EXPECT_EQ(text.rfind("lines: 200/200 lines (100%)", 0), 0u) << text;
  EXPECT_NE(text.find("done in"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
}

TEST(Progress, ReportsEveryAdvanceWhenIntervalIsZero) {
  std::ostringstream out;
  Progress progress("tiles", 3, "tiles", out, 0.0);
  progress.advance();
  progress.advance();
  progress.finish();
  progress.finish();
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3) << text;
  EXPECT_NE(text.find("tiles: 1/3 tiles (33%)"), std::string::npos) << text;
  EXPECT_NE(text.find("tiles: 2/3 tiles (67%)"), std::string::npos) << text;
}

TEST(Progress, UnknownTotalOmitsPercentAndEta) {
  std::ostringstream out;
  Progress progress("frames", 0, "frames", out, 1e9);
  progress.advance(7);
  const std::string line = progress.reportLine();
  EXPECT_EQ(line.rfind("frames: 7 frames,", 0), 0u) << line;
  EXPECT_EQ(line.find('%'), std::string::npos) << line;
  EXPECT_EQ(line.find("ETA"), std::string::npos) << line;
}

}  // namespace
}  // namespace hsmap
