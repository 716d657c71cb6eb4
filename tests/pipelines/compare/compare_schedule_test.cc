// The steps of a compare and their order (pipelines/compare/compare_schedule.h).

#include "pipelines/compare/compare_schedule.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "pipelines/compare/variant_list.h"

namespace hsmap {
namespace {

TEST(CompareSchedule, SequentialsSharedStagesComeFirstAndJointStartsAfterThem) {
  const auto plans = planCompare(allCompareVariants(), RunOptions{}, "survey files\n");
  const auto tasks = scheduleCompare(plans);
  ASSERT_EQ(tasks.size(), 5u);
  // 0: sequential up to surface; 1: joint after it; then stacked, planar and
  // the rest of sequential (after its first step).
  EXPECT_EQ(tasks[0].variant, 2u);
  EXPECT_EQ(tasks[0].until, "surface");
  EXPECT_TRUE(tasks[0].after.empty());
  EXPECT_EQ(tasks[1].variant, 3u);
  EXPECT_EQ(tasks[1].after, std::vector<std::size_t>{0});
  EXPECT_EQ(tasks[2].variant, 0u);
  EXPECT_EQ(tasks[3].variant, 1u);
  EXPECT_EQ(tasks[4].variant, 2u);
  EXPECT_TRUE(tasks[4].until.empty());
  EXPECT_EQ(tasks[4].after, std::vector<std::size_t>{0});
}

TEST(CompareSchedule, AVariantListSharingNothingIsOneStepEach) {
  const auto tasks = scheduleCompare(planCompare({Variant::planar, Variant::stacked}, RunOptions{}, ""));
  ASSERT_EQ(tasks.size(), 2u);
  EXPECT_TRUE(tasks[0].until.empty() && tasks[1].until.empty());
  EXPECT_TRUE(tasks[0].after.empty() && tasks[1].after.empty());
}

TEST(CompareSchedule, TasksRunAfterTheirDependenciesAtMostJobsAtATime) {
  const std::vector<CompareTask> tasks = {{0, "surface", {}}, {1, "", {0}}, {2, "", {}}, {3, "", {}}, {0, "", {0}}};
  std::mutex mutex;
  std::vector<std::size_t> order;
  std::atomic<int> running{0}, most{0};
  runTaskGraph(tasks, 2, [&](std::size_t t) {
    const int now = ++running;
    for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    {
      std::lock_guard lock(mutex);
      order.push_back(t);
    }
    --running;
  });
  ASSERT_EQ(order.size(), 5u);
  EXPECT_EQ(most.load(), 2);
  auto position = [&](std::size_t t) { return std::find(order.begin(), order.end(), t) - order.begin(); };
  EXPECT_LT(position(0), position(1));
  EXPECT_LT(position(0), position(4));

  order.clear();
  runTaskGraph(tasks, 1, [&](std::size_t t) { order.push_back(t); });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
}

}  // namespace
}  // namespace hsmap
