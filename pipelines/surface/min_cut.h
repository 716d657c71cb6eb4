#pragma once
// An s-t minimum cut on a plain graph description, solved by Boost Graph's
// boykov_kolmogorov_max_flow (Boykov & Kolmogorov 2004), the solver made
// for the many-short-paths graphs of vision. Nodes on the source side of
// the cut are "outside" (free space), on the sink side "inside" (matter).

#include <vector>

namespace hsmap {

struct CutGraph {
  // Per node: capacity of source -> node (cost of labelling it inside) and
  // of node -> sink (cost of labelling it outside).
  std::vector<double> source_capacity;
  std::vector<double> sink_capacity;
  // Undirected neighbour pairs with a capacity each way: a_to_b is paid
  // when a is outside and b inside.
  struct Link {
    int a = 0;
    int b = 0;
    double a_to_b = 0.0;
    double b_to_a = 0.0;
  };
  std::vector<Link> links;

  explicit CutGraph(int nodes = 0) : source_capacity(nodes, 0.0), sink_capacity(nodes, 0.0) {}
  int nodes() const { return static_cast<int>(source_capacity.size()); }
};

struct MinCut {
  std::vector<char> inside;  // per node: 1 on the sink side
  double flow = 0.0;         // the cut's cost
};

// Nodes that neither terminal reaches in the residual graph (their label
// costs nothing either way) are put outside.
MinCut solveMinCut(const CutGraph& graph);

}  // namespace hsmap
