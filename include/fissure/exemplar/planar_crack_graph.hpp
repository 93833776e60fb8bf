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
};

/// Signed area of a closed polygon (shoelace), positive counter-clockwise.
double polygon_area(const std::vector<Eigen::Vector2d>& outline);

}  // namespace fissure
