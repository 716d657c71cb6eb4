#include "pipelines/compare/compare_schedule.h"

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

namespace hsmap {

std::vector<CompareTask> scheduleCompare(const std::vector<VariantPlan>& plans) {
  std::vector<CompareTask> tasks;
  // The shared-stage step of each donor: up to the longest prefix any
  // variant takes from it.
  std::vector<std::optional<std::size_t>> shared_step(plans.size());
  for (std::size_t d = 0; d < plans.size(); ++d) {
    std::size_t longest = 0;
    for (const VariantPlan& plan : plans) {
      if (plan.donor == plans[d].variant) longest = std::max(longest, plan.shared.size());
    }
    if (longest == 0) continue;
    shared_step[d] = tasks.size();
    tasks.push_back({d, stageDefinition(variantStages(plans[d].variant)[longest - 1]).name, {}});
  }
  auto donor_index = [&](const VariantPlan& plan) {
    for (std::size_t d = 0; d < plans.size(); ++d) {
      if (plan.donor == plans[d].variant) return d;
    }
    return plans.size();
  };
  for (bool takers : {true, false}) {
    for (std::size_t v = 0; v < plans.size(); ++v) {
      const bool takes = plans[v].donor.has_value() && !plans[v].shared.empty();
      if (takes != takers) continue;
      CompareTask task{v, "", {}};
      if (shared_step[v]) task.after.push_back(*shared_step[v]);
      if (takes) task.after.push_back(*shared_step[donor_index(plans[v])]);
      tasks.push_back(task);
    }
  }
  return tasks;
}

void runTaskGraph(const std::vector<CompareTask>& tasks, int jobs, const std::function<void(std::size_t)>& run) {
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<bool> started(tasks.size(), false), finished(tasks.size(), false);
  std::size_t done = 0;
  auto worker = [&] {
    std::unique_lock lock(mutex);
    while (done < tasks.size()) {
      std::optional<std::size_t> next;
      for (std::size_t t = 0; t < tasks.size() && !next; ++t) {
        const bool ready = std::all_of(tasks[t].after.begin(), tasks[t].after.end(),
                                       [&](std::size_t before) { return finished[before]; });
        if (!started[t] && ready) next = t;
      }
      if (!next) {
        // Nothing ready: wait for a task to finish (or all to be taken).
        if (std::all_of(started.begin(), started.end(), [](bool s) { return s; })) break;
        changed.wait(lock);
        continue;
      }
      started[*next] = true;
      lock.unlock();
      run(*next);
      lock.lock();
      finished[*next] = true;
      ++done;
      changed.notify_all();
    }
  };
  std::vector<std::thread> workers;
  for (int j = 0; j < std::max(1, jobs); ++j) workers.emplace_back(worker);
  for (std::thread& thread : workers) thread.join();
}

}  // namespace hsmap
