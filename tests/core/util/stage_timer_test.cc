#include "core/util/stage_timer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <memory>
#include <thread>

namespace hsmap {
namespace {

TEST(StageTimings, RecordsStagesInOrderAndAccumulatesRepeats) {
  StageTimings timings;
  timings.record("load", 1.5);
  timings.record("solve", 2.0);
  timings.record("load", 0.5);
  ASSERT_EQ(timings.seconds().size(), 2u);
  EXPECT_EQ(timings.seconds()[0].first, "load");
  EXPECT_DOUBLE_EQ(timings.seconds()[0].second, 2.0);
  EXPECT_EQ(timings.seconds()[1].first, "solve");
  EXPECT_DOUBLE_EQ(timings.total(), 4.0);
}

TEST(StageTimings, GuardMeasuresWallTime) {
  StageTimings timings;
  {
    auto guard = timings.stage("sleep");
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  ASSERT_EQ(timings.seconds().size(), 1u);
  EXPECT_GE(timings.seconds()[0].second, 0.029);
  EXPECT_LT(timings.seconds()[0].second, 5.0);
}

TEST(PeakResidentMemory, GrowsWhenMemoryIsTouched) {
  const double before = peakResidentMemoryMb();
  EXPECT_GT(before, 0.0);
  constexpr std::size_t kBytes = 128u << 20;
  auto block = std::make_unique<char[]>(kBytes);
  std::memset(block.get(), 1, kBytes);
  volatile char sink = block[kBytes - 1];
  (void)sink;
  EXPECT_GE(peakResidentMemoryMb(), before + 100.0);
}

}  // namespace
}  // namespace hsmap
