#include "fissure/exemplar/planar_crack_graph.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <cmath>

namespace fissure {
namespace {

bool finite(const Eigen::Vector2d& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

std::string text(const Eigen::Vector2d& p) { return "(" + format_number(p.x()) + ", " + format_number(p.y()) + ")"; }

std::string indexed(const char* what, std::size_t index) { return std::string(what) + "[" + std::to_string(index) + "]"; }

// At most this many problems are listed in one message: a broken builder can produce thousands,
// and the first few say what is wrong.
constexpr std::size_t kMaxListedProblems = 5;

}  // namespace

double polyline_length(const std::vector<Eigen::Vector2d>& points) {
  double total = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) total += (points[i] - points[i - 1]).norm();
  return total;
}

double Crack::length() const { return polyline_length(points); }

double polygon_area(const std::vector<Eigen::Vector2d>& outline) {
  double twice = 0.0;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Eigen::Vector2d& a = outline[i];
    const Eigen::Vector2d& b = outline[(i + 1) % outline.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return twice / 2.0;
}

std::vector<std::string> PlanarCrackGraph::problems() const {
  std::vector<std::string> out;
  if (!std::isfinite(total_area) || !(total_area > 0.0)) out.push_back("total area " + format_number(total_area) + " is not positive and finite");
  if (!finite(frame_min) || !finite(frame_max) || !(frame_max.x() > frame_min.x()) || !(frame_max.y() > frame_min.y())) {
    out.push_back("frame " + text(frame_min) + " to " + text(frame_max) + " is not a finite rectangle with max > min");
  }
  if (!std::isfinite(crack_width) || crack_width < 0.0) out.push_back("crack width " + format_number(crack_width) + " is negative or not finite");
  // The end points' agreement with the node positions: exact for graphs from the builder; 1e-9 of
  // the frame's size leaves room for a caller's own round-off, far below any pixel or mesh scale.
  const double snap = 1e-9 * (finite(frame_max - frame_min) ? (frame_max - frame_min).norm() : 1.0);
  std::vector<int> ends(nodes.size(), 0);
  for (std::size_t c = 0; c < cracks.size(); ++c) {
    const Crack& crack = cracks[c];
    const std::string name = indexed("cracks", c);
    if (crack.points.size() < 2) out.push_back(name + " has " + std::to_string(crack.points.size()) + " points, fewer than 2");
    bool all_finite = true;
    for (std::size_t i = 0; i < crack.points.size() && all_finite; ++i) {
      if (!finite(crack.points[i])) {
        out.push_back(name + " point " + std::to_string(i) + " " + text(crack.points[i]) + " is not finite");
        all_finite = false;
      }
    }
    if (crack.start_node == -1 && crack.end_node == -1) continue;  // a closed crack meeting nothing
    bool in_range = true;
    for (const int node : {crack.start_node, crack.end_node}) {
      if (node < 0 || static_cast<std::size_t>(node) >= nodes.size()) {
        out.push_back(name + " names node " + std::to_string(node) + ", outside [0, " + std::to_string(nodes.size()) +
                      ") (-1 at both ends for a closed crack)");
        in_range = false;
      }
    }
    if (!in_range) continue;
    ++ends[static_cast<std::size_t>(crack.start_node)];
    ++ends[static_cast<std::size_t>(crack.end_node)];
    if (crack.points.size() >= 2 && all_finite) {
      const Eigen::Vector2d& start = nodes[static_cast<std::size_t>(crack.start_node)].position;
      const Eigen::Vector2d& end = nodes[static_cast<std::size_t>(crack.end_node)].position;
      if ((crack.points.front() - start).norm() > snap || (crack.points.back() - end).norm() > snap) {
        out.push_back(name + " runs from " + text(crack.points.front()) + " to " + text(crack.points.back()) +
                      ", not from its node " + text(start) + " to its node " + text(end));
      }
    }
  }
  for (std::size_t v = 0; v < nodes.size(); ++v) {
    const CrackNode& node = nodes[v];
    const std::string name = indexed("nodes", v);
    if (!finite(node.position)) out.push_back(name + " position " + text(node.position) + " is not finite");
    const int degree = ends[v];
    if (degree == 0) {
      out.push_back(name + " touches no crack");
    } else if (node.degree != degree) {
      out.push_back(name + " has degree " + std::to_string(node.degree) + " but " + std::to_string(degree) + " crack ends");
    }
    if ((node.kind == CrackNode::Kind::Junction) != (degree >= 3)) {
      out.push_back(name + (degree >= 3 ? " joins " + std::to_string(degree) + " crack ends but is not a junction"
                                        : " is a junction with only " + std::to_string(degree) + " crack ends"));
    }
  }
  double fragment_sum = 0.0;
  for (std::size_t f = 0; f < fragments.size(); ++f) {
    const Fragment& fragment = fragments[f];
    const std::string name = indexed("fragments", f);
    if (!std::isfinite(fragment.area) || !(fragment.area > 0.0)) out.push_back(name + " area " + format_number(fragment.area) + " is not positive and finite");
    else fragment_sum += fragment.area;
    if (!finite(fragment.centroid)) out.push_back(name + " centroid " + text(fragment.centroid) + " is not finite");
    for (const Eigen::Vector2d& p : fragment.outline) {
      if (!finite(p)) {
        out.push_back(name + " outline point " + text(p) + " is not finite");
        break;
      }
    }
  }
  // Fragments partition (at most) the fractured area; 1e-9 relative is summation round-off.
  if (std::isfinite(total_area) && total_area > 0.0 && fragment_sum > total_area * (1.0 + 1e-9)) {
    out.push_back("fragment areas sum to " + format_number(fragment_sum, 10) + ", more than the total area " +
                  format_number(total_area, 10));
  }
  return out;
}

void PlanarCrackGraph::validate() const {
  std::vector<std::string> list = problems();
  if (list.empty()) return;
  const std::size_t total = list.size();
  if (total > kMaxListedProblems) {
    list.resize(kMaxListedProblems);
    list.push_back("and " + std::to_string(total - kMaxListedProblems) + " more");
  }
  throw_if_problems((source.empty() ? std::string("crack graph") : source) + ": invalid crack graph", list);
}

PlanarCrackGraphBuilder::PlanarCrackGraphBuilder(const Eigen::Vector2d& frame_min, const Eigen::Vector2d& frame_max,
                                                 double total_area, std::string source) {
  m_graph.frame_min = frame_min;
  m_graph.frame_max = frame_max;
  m_graph.total_area = total_area;
  m_graph.source = std::move(source);
}

int PlanarCrackGraphBuilder::add_node(const Eigen::Vector2d& position, bool on_border) {
  CrackNode node;
  node.position = position;
  m_graph.nodes.push_back(node);
  m_on_border.push_back(on_border ? 1 : 0);
  return static_cast<int>(m_graph.nodes.size()) - 1;
}

void PlanarCrackGraphBuilder::add_crack(std::vector<Eigen::Vector2d> points, int start, int end) {
  m_graph.cracks.push_back(Crack{std::move(points), start, end});
}

void PlanarCrackGraphBuilder::add_fragment(Fragment fragment) { m_graph.fragments.push_back(std::move(fragment)); }

void PlanarCrackGraphBuilder::set_crack_width(double width) { m_graph.crack_width = width; }

PlanarCrackGraph PlanarCrackGraphBuilder::build() && {
  PlanarCrackGraph& g = m_graph;
  const auto node_count = static_cast<int>(g.nodes.size());
  auto valid = [&](int v) { return v >= 0 && v < node_count; };
  // Indices are checked against the nodes added, before unused nodes are dropped and renumbered.
  for (std::size_t c = 0; c < g.cracks.size(); ++c) {
    const Crack& crack = g.cracks[c];
    if (crack.start_node == -1 && crack.end_node == -1) continue;
    for (const int node : {crack.start_node, crack.end_node}) {
      if (!valid(node)) {
        throw InvalidInput((g.source.empty() ? std::string("crack graph") : g.source) + ": invalid crack graph: " +
                           indexed("cracks", c) + " names node " + std::to_string(node) + ", but " +
                           std::to_string(node_count) + " nodes were added");
      }
    }
  }
  std::vector<int> degree(g.nodes.size(), 0);
  for (const Crack& c : g.cracks) {
    if (!valid(c.start_node) || !valid(c.end_node)) continue;  // closed cracks
    ++degree[static_cast<std::size_t>(c.start_node)];
    ++degree[static_cast<std::size_t>(c.end_node)];
  }
  std::vector<int> new_id(g.nodes.size(), -1);
  std::vector<CrackNode> kept;
  for (std::size_t v = 0; v < g.nodes.size(); ++v) {
    if (degree[v] == 0) continue;
    CrackNode node = g.nodes[v];
    node.degree = degree[v];
    node.kind = node.degree >= 3 ? CrackNode::Kind::Junction : m_on_border[v] ? CrackNode::Kind::Border : CrackNode::Kind::End;
    new_id[v] = static_cast<int>(kept.size());
    kept.push_back(node);
  }
  g.nodes = std::move(kept);
  for (Crack& c : g.cracks) {
    if (!valid(c.start_node) || !valid(c.end_node)) continue;
    c.start_node = new_id[static_cast<std::size_t>(c.start_node)];
    c.end_node = new_id[static_cast<std::size_t>(c.end_node)];
    if (c.points.empty()) continue;
    c.points.front() = g.nodes[static_cast<std::size_t>(c.start_node)].position;
    c.points.back() = g.nodes[static_cast<std::size_t>(c.end_node)].position;
  }
  g.validate();
  return std::move(g);
}

}  // namespace fissure
