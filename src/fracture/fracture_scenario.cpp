#include "fissure/fracture/fracture_scenario.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/base/number_text.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace fissure {
namespace {

constexpr double kCos45 = 0.70710678118654752;

// Heights along up and the extent of the body across it.
struct Frame {
  Eigen::Vector3d up, a, b;  // up and two unit axes across it
  double low = 0.0, high = 0.0, across = 0.0;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Zero();  // the footprint across up (a, b)
};

Frame frame_of(const TetMesh& mesh, const Eigen::Vector3d& up) {
  Frame f;
  f.up = up.normalized();
  const Eigen::Vector3d helper = std::abs(f.up.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  f.a = f.up.cross(helper).normalized();
  f.b = f.up.cross(f.a);
  const Eigen::VectorXd h = mesh.nodes() * f.up, x = mesh.nodes() * f.a, y = mesh.nodes() * f.b;
  f.low = h.minCoeff();
  f.high = h.maxCoeff();
  f.across = std::max(x.maxCoeff() - x.minCoeff(), y.maxCoeff() - y.minCoeff());
  f.lo = {x.minCoeff(), y.minCoeff()};
  f.hi = {x.maxCoeff(), y.maxCoeff()};
  f.centre = 0.5 * (f.lo + f.hi);
  return f;
}

Eigen::Vector3d face_centre(const TetMesh& mesh, const BoundaryFace& face) {
  return (mesh.nodes().row(face.nodes[0]) + mesh.nodes().row(face.nodes[1]) + mesh.nodes().row(face.nodes[2]))
             .transpose() /
         3.0;
}

}  // namespace

Eigen::Vector3d parse_up_axis(const std::string& text) {
  std::string t = text;
  double sign = 1.0;
  if (!t.empty() && (t[0] == '+' || t[0] == '-')) {
    sign = t[0] == '-' ? -1.0 : 1.0;
    t = t.substr(1);
  }
  if (t == "x" || t == "X") return sign * Eigen::Vector3d::UnitX();
  if (t == "y" || t == "Y") return sign * Eigen::Vector3d::UnitY();
  if (t == "z" || t == "Z") return sign * Eigen::Vector3d::UnitZ();
  throw InvalidInput("--up " + text + " is not an axis: use +x, -x, +y, -y, +z or -z");
}

std::string up_axis_name(const Eigen::Vector3d& up) {
  if (up.isZero(0.0)) return "?";
  int axis = 0;
  up.cwiseAbs().maxCoeff(&axis);
  return std::string(up[axis] > 0.0 ? "+" : "-") + "xyz"[axis];
}

std::vector<int> default_support_dofs(const TetMesh& mesh, const Eigen::Vector3d& up) {
  const Frame f = frame_of(mesh, up);
  const double tolerance = 0.02 * (f.high - f.low);
  // The lowest face: down-facing boundary faces whose centre lies near the lowest height.
  std::map<std::pair<int, int>, int> edge_use;
  for (const BoundaryFace& face : mesh.boundary_faces()) {
    if (-face.normal.dot(f.up) < kCos45) continue;
    if (face_centre(mesh, face).dot(f.up) > f.low + tolerance) continue;
    for (int i = 0; i < 3; ++i) {
      const int a = face.nodes[static_cast<std::size_t>(i)], b = face.nodes[static_cast<std::size_t>((i + 1) % 3)];
      ++edge_use[{std::min(a, b), std::max(a, b)}];
    }
  }
  if (edge_use.empty()) {
    throw InvalidInput(mesh.source_name() + ": no boundary face looks down along the up axis, so the body has no face "
                       "to rest on; give --fix, --free or another --up");
  }
  // Its rim: edges used by one of its faces only.
  std::set<int> rim;
  for (const auto& [edge, uses] : edge_use) {
    if (uses == 1) {
      rim.insert(edge.first);
      rim.insert(edge.second);
    }
  }
  if (rim.size() < 3) {  // a closed lowest face (a sphere's cap) has no rim: hold all of it
    for (const auto& [edge, uses] : edge_use) {
      rim.insert(edge.first);
      rim.insert(edge.second);
    }
  }
  // Rollers along up: the up component of each rim node. `up` is an axis, so that is one dof.
  int axis = 0;
  f.up.cwiseAbs().maxCoeff(&axis);
  std::vector<int> dofs;
  for (int v : rim) dofs.push_back(3 * v + axis);
  // In-plane: the rim node nearest the centre across up is fixed in both in-plane directions,
  // the rim node farthest from it in the direction across the line between them.
  auto across_of = [&](int v) { return Eigen::Vector2d(mesh.nodes().row(v).dot(f.a), mesh.nodes().row(v).dot(f.b)); };
  int anchor = *rim.begin(), far = anchor;
  double best = std::numeric_limits<double>::infinity(), farthest = -1.0;
  for (int v : rim) {
    const double d = (across_of(v) - f.centre).norm();
    if (d < best) best = d, anchor = v;
  }
  for (int v : rim) {
    const double d = (across_of(v) - across_of(anchor)).norm();
    if (d > farthest) farthest = d, far = v;
  }
  for (int i = 0; i < 3; ++i) {
    if (i != axis) dofs.push_back(3 * anchor + i);
  }
  const Eigen::Vector2d line = across_of(far) - across_of(anchor);
  const Eigen::Vector3d normal_dir = (-line.y() * f.a + line.x() * f.b).normalized();
  const int i1 = (axis + 1) % 3, i2 = (axis + 2) % 3;
  const int component = std::abs(normal_dir(i1)) >= std::abs(normal_dir(i2)) ? i1 : i2;
  dofs.push_back(3 * far + component);
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  check_supports_for_mechanisms(mesh, dofs);
  return dofs;
}

std::vector<int> scenario_fixed_dofs(const TetMesh& mesh, const FractureScenario& scenario) {
  if (scenario.free_body) return {};
  if (!scenario.supports.empty()) return resolve_supports(mesh, scenario.supports);
  return default_support_dofs(mesh, scenario.up);
}

ScenarioLoads scenario_loads(const TetMesh& mesh, const FractureScenario& scenario) {
  ScenarioLoads out;
  if (scenario.loads.empty()) {
    out.loads = {default_load(mesh, scenario.up, 1.0, scenario.patch_radius)};
    out.default_load = true;
  } else {
    out.loads = scenario.loads;
  }
  out.unit_forces = Eigen::VectorXd::Zero(3 * mesh.node_count());
  for (const LoadSpec& load : out.loads) out.unit_forces += assemble_load(mesh, load);
  return out;
}

namespace {

// The patch on the up-facing boundary face nearest to `target` across up (the highest among
// faces as near): on a tile, right under it; on a basin, the rim or the bowl beneath.
LoadSpec top_face_load(const TetMesh& mesh, const Frame& f, const Eigen::Vector2d& target, double force, double patch_radius) {
  const BoundaryFace* best = nullptr;
  double best_d = std::numeric_limits<double>::infinity(), best_h = 0.0;
  for (const BoundaryFace& face : mesh.boundary_faces()) {
    if (face.normal.dot(f.up) < kCos45) continue;
    const Eigen::Vector3d c = face_centre(mesh, face);
    const double d = (Eigen::Vector2d(c.dot(f.a), c.dot(f.b)) - target).norm();
    const double h = c.dot(f.up);
    // Nearest to the target across up; among faces as near (within a millimetre's fraction of
    // the extent), the highest.
    if (d < best_d - 1e-6 * f.across || (std::abs(d - best_d) <= 1e-6 * f.across && h > best_h)) {
      best = &face;
      best_d = d;
      best_h = h;
    }
  }
  if (!best) {
    throw InvalidInput(mesh.source_name() + ": no boundary face looks up along the up axis, so there is no top face "
                       "for the default load; give --load or another --up");
  }
  return patch_load(mesh, f.up, face_centre(mesh, *best), force, patch_radius);
}

}  // namespace

LoadSpec default_load(const TetMesh& mesh, const Eigen::Vector3d& up, double force, double patch_radius) {
  const Frame f = frame_of(mesh, up);
  return top_face_load(mesh, f, f.centre, force, patch_radius);
}

LoadSpec drawn_load(const TetMesh& mesh, const Eigen::Vector3d& up, double force, std::uint64_t seed) {
  const Frame f = frame_of(mesh, up);
  Rng rng = Rng::derive(seed, "drawn-load");
  Eigen::Vector2d target;
  for (int k = 0; k < 2; ++k) {
    const double t = rng.uniform(kDrawnLoadInset, 1.0 - kDrawnLoadInset);
    target(k) = f.lo(k) + t * (f.hi(k) - f.lo(k));
  }
  return top_face_load(mesh, f, target, force, 0.0);
}

LoadSpec patch_load(const TetMesh& mesh, const Eigen::Vector3d& up, const Eigen::Vector3d& centre, double force,
                    double patch_radius) {
  const Frame f = frame_of(mesh, up);
  double radius = patch_radius > 0.0 ? patch_radius : 0.05 * f.across;
  // At least about two elements across, so the patch holds several faces.
  const double h = std::cbrt(6.0 * std::sqrt(2.0) * mesh.total_volume() / mesh.tet_count());
  radius = std::max(radius, 2.0 * h);
  const Eigen::Vector3d& c = centre;
  LoadSpec load;
  load.selection.kind = Selection::Kind::Ball;
  load.selection.center = c;
  load.selection.radius = radius;
  load.selection.spec = "ball:" + format_number(c.x()) + "," + format_number(c.y()) + "," + format_number(c.z()) + "," +
                        format_number(radius);
  load.normal = f.up;
  load.force = -force * f.up;
  load.spec = load.selection.spec + "^" + format_number(f.up.x()) + "," + format_number(f.up.y()) + "," +
              format_number(f.up.z()) + "=" + format_number(load.force.x()) + "," + format_number(load.force.y()) +
              "," + format_number(load.force.z());
  return load;
}

Eigen::Vector3d grid_load_position(const TetMesh& mesh, const Eigen::Vector3d& up, int grid, double inset, int k) {
  int axis = 0;
  up.cwiseAbs().maxCoeff(&axis);
  if (!(up.cwiseAbs() - Eigen::Vector3d::Unit(axis)).isZero(1e-12)) {
    throw InvalidInput("a fitted material's load rule lays its grid along the axes: the up direction must be one (+x, -y, …); give a load");
  }
  if (grid < 1) throw InvalidInput("the fitted load grid is empty");
  const int a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2;  // the two axes across up, in x, y, z order
  const Eigen::Matrix<double, 2, 3> box = mesh.bounding_box();
  const int i = k % grid, j = k / grid;
  const double fa = inset + (1.0 - 2.0 * inset) * (i + 0.5) / grid;
  const double fb = inset + (1.0 - 2.0 * inset) * (j + 0.5) / grid;
  Eigen::Vector3d centre;
  centre(a) = box(0, a) + fa * (box(1, a) - box(0, a));
  centre(b) = box(0, b) + fb * (box(1, b) - box(0, b));
  centre(axis) = up(axis) > 0 ? box(1, axis) : box(0, axis);
  return centre;
}

LoadSpec fitted_load(const TetMesh& mesh, const Eigen::Vector3d& up, int grid, double inset, double force,
                     std::uint64_t seed) {
  grid_load_position(mesh, up, grid, inset, 0);  // checks up and the grid before the draw
  Rng rng = Rng::derive(seed, "fit-load");
  const int k = static_cast<int>(rng.uniform_index(static_cast<std::uint64_t>(grid) * static_cast<std::uint64_t>(grid)));
  return patch_load(mesh, up, grid_load_position(mesh, up, grid, inset, k), force);
}

}  // namespace fissure
