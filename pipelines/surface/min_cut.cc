#include "pipelines/surface/min_cut.h"

#include <stdexcept>

// Boost Graph 1.74's edge iterators trip GCC 12's -Wmaybe-uninitialized.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#pragma GCC diagnostic pop

namespace hsmap {
namespace {

using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
using Graph = boost::adjacency_list<
    boost::vecS, boost::vecS, boost::directedS,
    boost::property<boost::vertex_index_t, long,
        boost::property<boost::vertex_color_t, boost::default_color_type,
            boost::property<boost::vertex_distance_t, long,
                boost::property<boost::vertex_predecessor_t, Traits::edge_descriptor>>>>,
    boost::property<boost::edge_capacity_t, double,
        boost::property<boost::edge_residual_capacity_t, double,
            boost::property<boost::edge_reverse_t, Traits::edge_descriptor>>>>;
using Vertex = boost::graph_traits<Graph>::vertex_descriptor;

// One arc u -> v with capacity c and its reverse v -> u with capacity c_back,
// each the other's reverse (how the Boost max-flow algorithms want them).
void addArcPair(Graph& g, Vertex u, Vertex v, double c, double c_back) {
  auto capacity = boost::get(boost::edge_capacity, g);
  auto reverse = boost::get(boost::edge_reverse, g);
  auto e = boost::add_edge(u, v, g).first;
  auto r = boost::add_edge(v, u, g).first;
  capacity[e] = c;
  capacity[r] = c_back;
  reverse[e] = r;
  reverse[r] = e;
}

}  // namespace

MinCut solveMinCut(const CutGraph& graph) {
  const int n = graph.nodes();
  if (graph.sink_capacity.size() != graph.source_capacity.size())
    throw std::invalid_argument("solveMinCut: source and sink capacities differ in count");
  Graph g(n + 2);
  const Vertex source = n, sink = n + 1;
  for (int i = 0; i < n; ++i) {
    if (graph.source_capacity[i] > 0.0) addArcPair(g, source, i, graph.source_capacity[i], 0.0);
    if (graph.sink_capacity[i] > 0.0) addArcPair(g, i, sink, graph.sink_capacity[i], 0.0);
  }
  for (const CutGraph::Link& link : graph.links) {
    if (link.a < 0 || link.a >= n || link.b < 0 || link.b >= n || link.a == link.b)
      throw std::invalid_argument("solveMinCut: a link names a node out of range or itself");
    if (link.a_to_b > 0.0 || link.b_to_a > 0.0) addArcPair(g, link.a, link.b, link.a_to_b, link.b_to_a);
  }
  MinCut cut;
  cut.flow = boost::boykov_kolmogorov_max_flow(g, source, sink);
  // Boost colours the source tree black and the sink tree white; free nodes
  // (gray) are reachable from neither and go outside.
  auto color = boost::get(boost::vertex_color, g);
  cut.inside.resize(n);
  for (int i = 0; i < n; ++i)
    cut.inside[i] = color[i] == boost::color_traits<boost::default_color_type>::white() ? 1 : 0;
  return cut;
}

}  // namespace hsmap
