#pragma once
/// Supports fix components of the selected nodes: `SEL` fixes x, y and z; `SEL@x`, `SEL@yz`, …
/// fix only the listed components (rollers). Fixed degrees of freedom are eliminated
/// (never penalised), through a DofMap. A support set that leaves a rigid motion free (a
/// mechanism) is refused, because every solver tried solves such a system silently and wrongly
/// (fem-pitfalls.md §2.1).

#include "fissure/fem/dof_map.hpp"
#include "fissure/fem/selection.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace fissure {

/// One support: a selection and the components it fixes.
struct SupportSpec {
  std::string spec;
  Selection selection;
  std::array<bool, 3> components{true, true, true};
};

/// Parses `SEL` or `SEL@xyz` (any non-empty subset of x, y, z). Throws InvalidInput naming the
/// spec when malformed.
SupportSpec parse_support(std::string_view spec);

/// The dofs fixed by a list of supports (sorted, unique; dof 3·v + i). Throws InvalidInput naming
/// a support that selects no node.
std::vector<int> resolve_supports(const TetMesh& mesh, const std::vector<SupportSpec>& supports);

/// All three dofs of each node.
std::vector<int> dofs_of_nodes(const std::vector<int>& nodes);

/// Throws InvalidInput when the fixed dofs leave a rigid motion free in some connected component,
/// naming the component and the number of free rigid motions, e.g.
/// "supports leave 1 rigid motion free in component 0 (the fixed nodes are collinear)". With no
/// fixed dof at all the body is free (inertia relief) and nothing is thrown.
void check_supports_for_mechanisms(const TetMesh& mesh, const std::vector<int>& fixed_dofs);

}  // namespace fissure
