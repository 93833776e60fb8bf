#pragma once
/// How a body is held and struck for a fracture run, with defaults that work on any closed body
/// (docs/architecture.md, "Fracture simulation"):
///  - supports: rollers along `up` on the rim of the lowest face (the boundary faces facing down,
///    within 45° of −up, at the lowest height, give or take 2 % of the body's height), plus the
///    fewest in-plane constraints that stop rigid motion (one node fixed, one more held
///    against rotation about up). A body resting on its rim bends under a load on top, which is
///    what breaks a tile or a basin; clamping the whole face would carry the load in compression
///    and break nothing. `free_body` instead uses inertia relief (nothing held);
///  - load: one patch at the centre of the top face (the up-facing face nearest to the body's
///    centre across up), pushing down with |f| = l · m_body · g, over a disc of radius
///    `patch_radius` (default 5 % of the body's largest extent across up, at least 2 element
///    sizes).
#include "fissure/fem/load.hpp"
#include "fissure/fem/supports.hpp"
#include "fissure/fracture/fracture_params.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace fissure {

constexpr double kStandardGravity = 9.80665;  ///< m/s², the load factor l's g

struct FractureScenario {
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();  ///< unit; the visible face looks along it
  bool free_body = false;
  std::vector<SupportSpec> supports;  ///< empty and not free: the default rim rollers
  std::vector<LoadSpec> loads;        ///< empty: the default patch, scaled by l
  double patch_radius = 0.0;          ///< m; 0: the default
};

/// The default supports above, as fixed dofs (sorted). Throws InvalidInput when the body has no
/// face looking down along −up within 45° (say --free or give --fix).
std::vector<int> default_support_dofs(const TetMesh& mesh, const Eigen::Vector3d& up);

/// The dofs a scenario holds (sorted): none for a free body, its supports resolved on the mesh,
/// else the default rim rollers. Throws InvalidInput as resolve_supports() and
/// default_support_dofs() do.
std::vector<int> scenario_fixed_dofs(const TetMesh& mesh, const FractureScenario& scenario);

/// The loads a scenario applies: its own as given, or (none given) the default patch for 1 N,
/// which a run scales by l·m_body·g.
struct ScenarioLoads {
  std::vector<LoadSpec> loads;
  bool default_load = false;
  Eigen::VectorXd unit_forces;  ///< their nodal forces summed (3 per node, N)
};
ScenarioLoads scenario_loads(const TetMesh& mesh, const FractureScenario& scenario);

/// The default load above for magnitude `force` (N), as a LoadSpec (a ball selection with up as
/// its reference normal). Throws InvalidInput when no boundary face looks up within 45°.
LoadSpec default_load(const TetMesh& mesh, const Eigen::Vector3d& up, double force, double patch_radius = 0.0);

/// The margin of a body's footprint where no drawn load lands (drawn_load(), and the fit's
/// load grid, fit_body.hpp): a blow right on the edge chips rather than cracks the face.
inline constexpr double kDrawnLoadInset = 0.15;

/// The default load at a drawn point instead of the centre: a point uniform over [inset,
/// 1 − inset] of each side of the body's footprint across up, drawn from (seed, "drawn-load"),
/// and the patch on the up-facing face nearest to it, pushing with `force`. What a scene body
/// with no loads and an unfitted material gets, so bodies sharing a material are not all struck
/// at their centres. Throws InvalidInput as default_load() does.
LoadSpec drawn_load(const TetMesh& mesh, const Eigen::Vector3d& up, double force, std::uint64_t seed);

/// A patch load like the default one but centred at `centre` (a point of the top face): radius
/// `patch_radius` (0: 5 % of the body's largest extent across up), at least 2 element sizes,
/// pushing with `force` (N) along −up. The fit's load at a drawn position.
LoadSpec patch_load(const TetMesh& mesh, const Eigen::Vector3d& up, const Eigen::Vector3d& centre, double force,
                    double patch_radius = 0.0);

/// Centre of cell k of a `grid` × `grid` grid over [inset, 1 − inset] of the body's bounding box
/// across `up`, at the box's top along up: the fit's load positions. `up` is a coordinate axis
/// (±x, ±y, ±z); the grid's axes are the other two in x, y, z order, the first running fastest
/// (for +z: row-major, x fastest, as the fit's tiles have always used). Throws InvalidInput when
/// up is not a coordinate axis.
Eigen::Vector3d grid_load_position(const TetMesh& mesh, const Eigen::Vector3d& up, int grid, double inset, int k);

/// The load a fitted material's rule draws for a body (MaterialFit's load rule, the fit's trials'
/// law): the patch at a cell of the grid drawn from (seed, "fit-load"), pushing with `force`.
/// Throws InvalidInput when up is not a coordinate axis (the grid is laid along the axes).
LoadSpec fitted_load(const TetMesh& mesh, const Eigen::Vector3d& up, int grid, double inset, double force,
                     std::uint64_t seed);

/// Parses "+x", "-y", "z" (= "+z"), … as a unit axis. Throws InvalidInput naming the text.
Eigen::Vector3d parse_up_axis(const std::string& text);

/// "+x", "-z", …: the axis of a vector's largest component, with its sign ("?" for zero).
std::string up_axis_name(const Eigen::Vector3d& up);

}  // namespace fissure
