#pragma once
/// The planar crack pattern both halves of Fissure produce: an exemplar image's crack graph and
/// (later) a simulation's visible surface cracks. PatternStats are computed from this type only,
/// so image and simulation are measured by the same definitions.

#include <Eigen/Core>

#include <string>
#include <vector>

namespace fissure {

/// A node where cracks end or meet. Positions are in the graph's own units (pixels for an image,
/// metres for a simulation).
struct CrackNode {
  enum class Kind {
    Junction,  ///< three or more cracks meet
    End,       ///< a crack stops inside the fractured area
    Border,    ///< a crack leaves the fractured area (image frame or ROI edge)
  };
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Kind kind = Kind::End;
  int degree = 0;  ///< number of crack ends at this node (a loop through it counts twice)
};

/// One crack: a polyline between two nodes (start_node == end_node for a loop through a node;
/// both −1 for a closed crack that meets nothing).
struct Crack {
  std::vector<Eigen::Vector2d> points;  ///< from the start node's position to the end node's
  int start_node = -1;
  int end_node = -1;
  double length() const;
};

/// A region enclosed by cracks (and possibly by the border of the fractured area).
struct Fragment {
  double area = 0.0;           ///< graph units²
  bool touches_border = false; ///< cut by the image frame or ROI edge: its true size is unknown
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  /// Optional outline (a simulation's fragment polygon); empty for image fragments.
  std::vector<Eigen::Vector2d> outline;
};

struct PlanarCrackGraph {
  std::vector<CrackNode> nodes;
  std::vector<Crack> cracks;
  std::vector<Fragment> fragments;
  /// Total fractured area (graph units²): the image or ROI area, or the simulated visible face.
  double total_area = 0.0;
  /// The rectangle the pattern lives in: min corner and max corner (for the junction-window
  /// statistic).
  Eigen::Vector2d frame_min = Eigen::Vector2d::Zero();
  Eigen::Vector2d frame_max = Eigen::Vector2d::Zero();
  /// Typical crack width in graph units (0 when unknown); sets the junction-angle probe.
  double crack_width = 0.0;
  std::string source;

  /// Readable problems, empty when the graph is consistent: a positive finite total area; a
  /// frame with frame_max > frame_min, finite; a finite crack width ≥ 0; nodes at finite
  /// positions, each touched by a crack, whose degree is the number of crack ends at it and whose
  /// kind is Junction exactly when the degree is ≥ 3; cracks of ≥ 2 finite points whose node
  /// indices are both in range (or both −1 for a closed crack)
  /// and whose end points are their nodes' positions; fragments of positive finite area and
  /// finite centroid and outline, together no larger than the total area. Entities are named by
  /// their index ("cracks[3]"). O(nodes + points + fragments).
  std::vector<std::string> problems() const;
  /// Throws InvalidInput "<source>: <problem>" (the first problems) when problems() is not empty.
  /// Called at the entry of every function that consumes a graph.
  void validate() const;
};

/// Builds a consistent PlanarCrackGraph (what a simulation's crack extraction will use): the
/// caller adds nodes and cracks, the builder derives each node's degree and kind from the cracks
/// (degree ≥ 3: Junction; else Border when the node was added as on the border, else End), drops
/// nodes no crack touches (renumbering the rest in order), snaps each crack's end points to its
/// nodes' positions and validates the result. Node indices passed to add_crack are the ones
/// add_node returned.
class PlanarCrackGraphBuilder {
public:
  /// The frame (min and max corner) and the total fractured area, in graph units; `source` names
  /// the pattern in messages.
  PlanarCrackGraphBuilder(const Eigen::Vector2d& frame_min, const Eigen::Vector2d& frame_max, double total_area,
                          std::string source);
  /// A node where cracks end or meet; `on_border` = it lies on the edge of the fractured area.
  int add_node(const Eigen::Vector2d& position, bool on_border = false);
  /// A crack from node `start` to node `end` (equal for a loop through one node), or a closed
  /// crack meeting nothing when both are −1.
  void add_crack(std::vector<Eigen::Vector2d> points, int start, int end);
  void add_fragment(Fragment fragment);
  void set_crack_width(double width);
  /// The graph; throws InvalidInput naming the source and the first problems (a crack naming a
  /// node that was never added, a non-finite point, a fragment of no area, …).
  PlanarCrackGraph build() &&;

private:
  PlanarCrackGraph m_graph;
  std::vector<char> m_on_border;
};

/// Length of a polyline: the sum of its segment lengths (0 for fewer than two points).
double polyline_length(const std::vector<Eigen::Vector2d>& points);

/// Signed area of a closed polygon (shoelace), positive counter-clockwise.
double polygon_area(const std::vector<Eigen::Vector2d>& outline);

}  // namespace fissure
