#include "fissure/fem/supports.hpp"

#include "fissure/base/error.hpp"
#include "fissure/fem/rigid_modes.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <string>

namespace fissure {

SupportSpec parse_support(std::string_view spec) {
  SupportSpec support;
  support.spec = std::string(spec);
  const std::size_t at = spec.rfind('@');
  std::string_view selection = spec;
  if (at != std::string_view::npos) {
    const std::string_view axes = spec.substr(at + 1);
    selection = spec.substr(0, at);
    if (axes.empty() || axes.size() > 3 || axes.find_first_not_of("xyz") != std::string_view::npos) {
      throw InvalidInput("support '" + support.spec +
                         "': after '@' list the fixed components, e.g. @x, @yz or @xyz");
    }
    support.components = {false, false, false};
    for (char c : axes) support.components[static_cast<std::size_t>(c - 'x')] = true;
  }
  support.selection = parse_selection(selection);
  return support;
}

std::vector<int> dofs_of_nodes(const std::vector<int>& nodes) {
  std::vector<int> dofs;
  dofs.reserve(nodes.size() * 3);
  for (int v : nodes)
    for (int i = 0; i < 3; ++i) dofs.push_back(3 * v + i);
  return dofs;
}

std::vector<int> resolve_supports(const TetMesh& mesh, const std::vector<SupportSpec>& supports) {
  std::vector<int> fixed;
  for (const SupportSpec& s : supports) {
    const SelectedRegion region = resolve_selection(mesh, s.selection);
    if (region.nodes.empty()) {
      throw InvalidInput("support '" + s.spec + "' selects no node of " +
                         (mesh.source_name().empty() ? std::string("the mesh") : mesh.source_name()));
    }
    for (int v : region.nodes)
      for (int i = 0; i < 3; ++i)
        if (s.components[static_cast<std::size_t>(i)]) fixed.push_back(3 * v + i);
  }
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  return fixed;
}

void check_supports_for_mechanisms(const TetMesh& mesh, const std::vector<int>& fixed_dofs) {
  check_fixed_dofs(mesh, fixed_dofs);
  if (fixed_dofs.empty()) return;  // a free body: solved by inertia relief
  const auto groups = nodes_by_component(mesh);
  const auto component_of_node = mesh.component_of_node();
  // Fixed nodes per component, and the rows (dofs) of the rigid modes they constrain.
  std::vector<std::vector<int>> fixed_by_component(groups.size());
  std::vector<std::vector<int>> rows_by_component(groups.size());
  std::vector<int> sorted_dofs = fixed_dofs;
  std::sort(sorted_dofs.begin(), sorted_dofs.end());
  sorted_dofs.erase(std::unique(sorted_dofs.begin(), sorted_dofs.end()), sorted_dofs.end());
  // Nothing left free: no load can deform it (the solver met an empty system and said "out of
  // memory?").
  if (static_cast<Eigen::Index>(sorted_dofs.size()) == 3 * static_cast<Eigen::Index>(mesh.node_count())) {
    throw InvalidInput("the supports fix every node of " +
                       (mesh.source_name().empty() ? std::string("the mesh") : mesh.source_name()) +
                       ": nothing is left to move or to crack; fix a part of it (a face, a box)");
  }
  for (int dof : sorted_dofs) {
    const int v = dof / 3;
    const std::size_t c = static_cast<std::size_t>(component_of_node[v]);
    if (fixed_by_component[c].empty() || fixed_by_component[c].back() != v) {
      fixed_by_component[c].push_back(v);
    }
    rows_by_component[c].push_back(3 * (static_cast<int>(fixed_by_component[c].size()) - 1) + dof % 3);
  }

  for (std::size_t c = 0; c < groups.size(); ++c) {
    const auto& fixed = fixed_by_component[c];
    int rank = 0;
    if (!fixed.empty()) {
      const Eigen::MatrixXd all = rigid_body_modes_at(mesh.nodes(), fixed, node_frame(mesh, groups[c]));
      const auto& rows = rows_by_component[c];
      Eigen::MatrixXd r(static_cast<Eigen::Index>(rows.size()), 6);
      for (std::size_t k = 0; k < rows.size(); ++k) r.row(static_cast<Eigen::Index>(k)) = all.row(rows[k]);
      const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(r).singularValues();
      // The columns are O(1) per node (rotations divided by the body size), so σ_max ~ √#fixed.
      // Collinear or coincident fixed nodes leave singular values at round-off (~1e-16·σ_max);
      // any two distinct mesh nodes are at least ~1e-6 of the body size apart, which gives
      // σ ≳ 1e-6. A relative threshold of 1e-10 separates the two by four decades either way.
      for (Eigen::Index i = 0; i < sigma.size(); ++i) rank += sigma[i] > 1e-10 * sigma[0];
    }
    if (rank < 6) {
      const int free_motions = 6 - rank;
      std::string why;
      if (fixed.empty()) {
        why = "it has no support while other components do";
      } else if (rank == 3 && fixed.size() == 1) {
        why = "only one point is fixed";
      } else if (rank == 5 && rows_by_component[c].size() == 3 * fixed.size()) {
        why = "the fixed nodes are collinear";
      } else {
        why = "the fixed nodes do not stop every rigid motion";
      }
      throw InvalidInput("supports leave " + std::to_string(free_motions) + " rigid motion" +
                         (free_motions > 1 ? "s" : "") + " free in component " + std::to_string(c) +
                         " of " + std::to_string(groups.size()) + " (" + why + ")");
    }
  }
}

}  // namespace fissure
