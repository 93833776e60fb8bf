#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/exemplar/histogram.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace fissure {
namespace {

Histogram random_histogram(Rng& rng, int bins, double zero_fraction = 0.3) {
  Histogram h = Histogram::make(0.0, 1.0, bins);
  for (double& p : h.p) p = rng.uniform() < zero_fraction ? 0.0 : rng.uniform();
  if (h.total() == 0.0) h.p[0] = 1.0;
  h.normalize();
  return h;
}

// The transportation problem solved directly, independently of the CDF formula: successive
// shortest augmenting paths (Bellman–Ford on the residual graph) moving mass from a's bins to
// b's at cost |i − j|·Δ / range. Exact for any real supplies; fine for a handful of bins.
double brute_force_transport(const Histogram& a, const Histogram& b) {
  const int n = static_cast<int>(a.p.size());
  // Nodes: source 0, a-bins 1..n, b-bins n+1..2n, sink 2n+1.
  struct Edge {
    int to;
    double capacity, cost;
    int reverse;
  };
  std::vector<std::vector<Edge>> graph(2 * n + 2);
  auto add = [&](int u, int v, double capacity, double cost) {
    graph[u].push_back({v, capacity, cost, static_cast<int>(graph[v].size())});
    graph[v].push_back({u, 0.0, -cost, static_cast<int>(graph[u].size()) - 1});
  };
  for (int i = 0; i < n; ++i) add(0, 1 + i, a.p[i], 0.0);
  for (int j = 0; j < n; ++j) add(1 + n + j, 2 * n + 1, b.p[j], 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) add(1 + i, 1 + n + j, 1e9, std::abs(i - j) / static_cast<double>(n));
  double total_cost = 0.0, flow = 0.0;
  while (flow < 1.0 - 1e-12) {
    std::vector<double> dist(graph.size(), std::numeric_limits<double>::infinity());
    std::vector<std::pair<int, int>> parent(graph.size(), {-1, -1});
    dist[0] = 0.0;
    for (std::size_t round = 0; round < graph.size(); ++round) {
      bool relaxed = false;
      for (std::size_t u = 0; u < graph.size(); ++u) {
        if (dist[u] == std::numeric_limits<double>::infinity()) continue;
        for (std::size_t e = 0; e < graph[u].size(); ++e) {
          const Edge& edge = graph[u][e];
          if (edge.capacity > 1e-15 && dist[u] + edge.cost < dist[edge.to] - 1e-15) {
            dist[edge.to] = dist[u] + edge.cost;
            parent[edge.to] = {static_cast<int>(u), static_cast<int>(e)};
            relaxed = true;
          }
        }
      }
      if (!relaxed) break;
    }
    const int sink = 2 * n + 1;
    if (parent[sink].first < 0) break;
    double push = 1.0 - flow;
    for (int v = sink; v != 0; v = parent[v].first) push = std::min(push, graph[parent[v].first][parent[v].second].capacity);
    for (int v = sink; v != 0; v = parent[v].first) {
      Edge& edge = graph[parent[v].first][parent[v].second];
      edge.capacity -= push;
      graph[v][edge.reverse].capacity += push;
    }
    flow += push;
    total_cost += push * dist[sink];
  }
  return total_cost;
}

TEST(Emd, ZeroOnIdenticalAndSymmetric) {
  Rng rng(1);
  for (int trial = 0; trial < 200; ++trial) {
    const Histogram a = random_histogram(rng, 12), b = random_histogram(rng, 12);
    EXPECT_EQ(earth_movers_distance(a, a), 0.0);
    EXPECT_DOUBLE_EQ(earth_movers_distance(a, b), earth_movers_distance(b, a));
    EXPECT_GT(earth_movers_distance(a, b), 0.0);
  }
}

TEST(Emd, TriangleInequality) {
  Rng rng(2);
  for (int trial = 0; trial < 1000; ++trial) {
    const Histogram a = random_histogram(rng, 16), b = random_histogram(rng, 16), c = random_histogram(rng, 16);
    // Round-off of three sums of 16 terms: 1e-14.
    EXPECT_LE(earth_movers_distance(a, c), earth_movers_distance(a, b) + earth_movers_distance(b, c) + 1e-14);
  }
}

TEST(Emd, EqualsTheTransportOptimum) {
  Rng rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    const int bins = 2 + static_cast<int>(rng.uniform_index(5));
    const Histogram a = random_histogram(rng, bins), b = random_histogram(rng, bins);
    // The flow solver accumulates ~bins² shortest paths: 1e-12 absolute.
    EXPECT_NEAR(earth_movers_distance(a, b), brute_force_transport(a, b), 1e-12) << "bins " << bins;
  }
}

TEST(Emd, KnownValuesAndBadBins) {
  Histogram a = Histogram::make(0.0, 4.0, 4), b = a;
  a.p = {1, 0, 0, 0};
  b.p = {0, 0, 0, 1};
  EXPECT_DOUBLE_EQ(earth_movers_distance(a, b), 0.75);  // 3 bins of 1 over a range of 4
  b.p = {0, 1, 0, 0};
  EXPECT_DOUBLE_EQ(earth_movers_distance(a, b), 0.25);
  Histogram other = Histogram::make(0.0, 5.0, 4);
  EXPECT_THROW(earth_movers_distance(a, other, "test"), InvalidInput);
  // Out-of-range values land in the end bins; nothing is lost.
  Histogram h = Histogram::make(0.0, 1.0, 4);
  h.add(-5.0);
  h.add(7.0);
  EXPECT_DOUBLE_EQ(h.p.front(), 1.0);
  EXPECT_DOUBLE_EQ(h.p.back(), 1.0);
}

}  // namespace
}  // namespace fissure
