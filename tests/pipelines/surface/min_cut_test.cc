// solveMinCut: Boost's Boykov-Kolmogorov max-flow on a plain graph.
#include "pipelines/surface/min_cut.h"

#include <gtest/gtest.h>

namespace hsmap {
namespace {

TEST(MinCut, CutsTheCheapestLinkOfAChain) {
  // source -> 0 -> 1 -> 2 -> sink, the link 1 -> 2 the cheapest.
  CutGraph graph(3);
  graph.source_capacity[0] = 10.0;
  graph.sink_capacity[2] = 10.0;
  graph.links.push_back({0, 1, 5.0, 0.0});
  graph.links.push_back({1, 2, 2.0, 0.0});
  const MinCut cut = solveMinCut(graph);
  EXPECT_DOUBLE_EQ(cut.flow, 2.0);
  EXPECT_EQ(cut.inside, (std::vector<char>{0, 0, 1}));
}

TEST(MinCut, ALinkCostsOnlyInItsOwnDirection) {
  // 0 -> 1 is free, 1 -> 0 costly: labelling 0 inside and 1 outside is cheap.
  CutGraph graph(2);
  graph.sink_capacity[0] = 3.0;
  graph.source_capacity[1] = 3.0;
  graph.links.push_back({0, 1, 100.0, 0.0});
  const MinCut cut = solveMinCut(graph);
  EXPECT_DOUBLE_EQ(cut.flow, 0.0);
  EXPECT_EQ(cut.inside, (std::vector<char>{1, 0}));
}

TEST(MinCut, NodesTiedToNoTerminalAreOutside) {
  CutGraph graph(3);
  graph.sink_capacity[0] = 1.0;
  const MinCut cut = solveMinCut(graph);
  EXPECT_EQ(cut.inside, (std::vector<char>{1, 0, 0}));
}

TEST(MinCut, RejectsALinkOutOfRange) {
  CutGraph graph(2);
  graph.links.push_back({0, 2, 1.0, 1.0});
  EXPECT_THROW(solveMinCut(graph), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
