// Step 5 of extract_crack_graph: pruning the raw skeleton graph (crack_graph_steps.hpp).

#include "crack_graph_steps.hpp"

#include <algorithm>

namespace fissure::detail {
namespace {

using Incidence = std::vector<std::vector<int>>;

int degree_of(const Incidence& inc, int v) { return v < 0 ? 0 : static_cast<int>(inc[static_cast<std::size_t>(v)].size()); }

// Spurs (a free end to a junction), specks (free end to free end) shorter than the spur length,
// and loops through one node shorter than twice it. `inc` is the index at the start of the pass:
// edges removed in this pass still count in the degrees.
bool remove_short_branches(PruningGraph& g, const Incidence& inc,
                           const std::function<bool(const Eigen::Vector2d&)>& near_border, CrackGraphDiagnostics& diag) {
  bool changed = false;
  auto degree = [&](int v) { return degree_of(inc, v); };
  auto free_end = [&](int v) { return v >= 0 && degree(v) == 1 && !near_border(g.nodes[static_cast<std::size_t>(v)].position); };
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    RawEdge& edge = g.edges[e];
    if (!edge.alive || edge.a < 0) continue;
    const double length = edge.length();
    if (edge.a == edge.b) {
      if (length < 2.0 * diag.spur_length_px) {
        edge.alive = false;
        ++diag.tiny_loops_removed;
        changed = true;
      }
      continue;
    }
    const bool a_free = free_end(edge.a), b_free = free_end(edge.b);
    if ((a_free || b_free) && length < diag.spur_length_px) {
      if (a_free && b_free) {
        ++diag.specks_removed;
      } else if (degree(a_free ? edge.b : edge.a) >= 3) {
        ++diag.spurs_pruned;
      } else {
        continue;  // a short crack from a free end to the border: keep it
      }
      edge.alive = false;
      changed = true;
    }
  }
  return changed;
}

bool splice_two_crack_nodes(PruningGraph& g, Incidence& inc) {
  bool changed = false;
  // Splice nodes left with two crack ends, drop nodes left with none.
  for (std::size_t v = 0; v < g.nodes.size(); ++v) {
    if (!g.nodes[v].alive) continue;
    const auto& list = inc[v];
    if (list.empty()) {
      g.nodes[v].alive = false;
      continue;
    }
    if (list.size() != 2 || list[0] == list[1] || g.nodes[v].is_end) continue;
    const int list_first = list[0], list_second = list[1];
    RawEdge& first = g.edges[static_cast<std::size_t>(list_first)];
    RawEdge& second = g.edges[static_cast<std::size_t>(list_second)];
    // Orient first to end at v and second to start at v, then concatenate.
    if (first.b != static_cast<int>(v)) {
      std::reverse(first.points.begin(), first.points.end());
      std::swap(first.a, first.b);
    }
    if (second.a != static_cast<int>(v)) {
      std::reverse(second.points.begin(), second.points.end());
      std::swap(second.a, second.b);
    }
    first.points.insert(first.points.end(), second.points.begin() + 1, second.points.end());
    first.b = second.b;
    second.alive = false;
    g.nodes[v].alive = false;
    if (first.a == static_cast<int>(v) && first.b == static_cast<int>(v)) first.a = first.b = -1;  // now a closed loop
    // Update the index in place (a rebuild per splice made pruning quadratic in the cracks):
    // v loses both edges, and second's far end now ends `first` instead.
    inc[v].clear();
    if (first.b >= 0) {
      auto& far = inc[static_cast<std::size_t>(first.b)];
      std::replace(far.begin(), far.end(), list_second, list_first);
    }
    changed = true;
  }
  return changed;
}

bool contract_close_junctions(PruningGraph& g, Incidence& inc, CrackGraphDiagnostics& diag) {
  bool changed = false;
  auto degree = [&](int v) { return degree_of(inc, v); };
  // Contract junction pairs joined by a crack shorter than the crack width, in one sweep that
  // keeps the node → edges index current (restarting the sweep after each contraction, and
  // relabelling over all edges, made dense networks quadratic: 207 s for a 4096² grid).
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    RawEdge& edge = g.edges[e];
    if (!edge.alive || edge.a < 0 || edge.a == edge.b) continue;
    if (degree(edge.a) < 3 || degree(edge.b) < 3 || edge.length() >= diag.merge_length_px) continue;
    const int from = edge.b, to = edge.a;
    RawNode& keep = g.nodes[static_cast<std::size_t>(to)];
    RawNode& gone = g.nodes[static_cast<std::size_t>(from)];
    keep.position = 0.5 * (keep.position + gone.position);
    gone.alive = false;
    edge.alive = false;
    auto& at_to = inc[static_cast<std::size_t>(to)];
    auto& at_from = inc[static_cast<std::size_t>(from)];
    at_to.erase(std::find(at_to.begin(), at_to.end(), static_cast<int>(e)));
    at_from.erase(std::find(at_from.begin(), at_from.end(), static_cast<int>(e)));
    for (int o : at_from) {
      RawEdge& other = g.edges[static_cast<std::size_t>(o)];
      if (other.a == from) other.a = to;
      if (other.b == from) other.b = to;
    }
    at_to.insert(at_to.end(), at_from.begin(), at_from.end());
    at_from.clear();
    for (int o : at_to) {
      RawEdge& other = g.edges[static_cast<std::size_t>(o)];
      if (other.a == to) other.points.front() = keep.position;
      if (other.b == to) other.points.back() = keep.position;
    }
    ++diag.junctions_contracted;
    changed = true;
  }
  return changed;
}

}  // namespace

void prune_graph(PruningGraph& g, const std::function<bool(const Eigen::Vector2d&)>& near_border, CrackGraphDiagnostics& diag) {
  // Prune until nothing changes: spurs and specks, tiny loops, then contract close junctions.
  bool changed = true;
  while (changed) {
    auto inc = g.incidence();
    changed = remove_short_branches(g, inc, near_border, diag);
    if (changed) inc = g.incidence();
    changed = splice_two_crack_nodes(g, inc) || changed;
    changed = contract_close_junctions(g, inc, diag) || changed;
  }
}

}  // namespace fissure::detail
