#include "fissure/fem/load.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace fissure {
namespace {

std::string mesh_name(const TetMesh& mesh) {
  return mesh.source_name().empty() ? std::string("the mesh") : mesh.source_name();
}

// The point a box or ball selection is centred on.
std::optional<Eigen::Vector3d> selection_centre(const Selection& s) {
  if (s.kind == Selection::Kind::Ball) return s.center;
  if (s.kind == Selection::Kind::Box) {
    return Eigen::Vector3d(0.5 * (s.box[0] + s.box[1]), 0.5 * (s.box[2] + s.box[3]), 0.5 * (s.box[4] + s.box[5]));
  }
  return std::nullopt;
}

}  // namespace

LoadSpec parse_load(std::string_view spec) {
  LoadSpec load;
  load.spec = std::string(spec);
  const std::size_t eq = spec.rfind('=');
  if (eq == std::string_view::npos || eq == 0) {
    throw InvalidInput("load '" + load.spec + "': expected SELECTION=fx,fy,fz (newtons), optionally SELECTION^nx,ny,nz=...");
  }
  std::string_view selection = spec.substr(0, eq);
  const std::size_t caret = selection.rfind('^');
  if (caret != std::string_view::npos) {
    const auto n = parse_number_list(selection.substr(caret + 1), "load '" + load.spec + "': normal", 3, "nx,ny,nz");
    const Eigen::Vector3d normal(n[0], n[1], n[2]);
    // The normal is a direction: scale it first so its norm neither overflows nor underflows.
    const double largest = normal.cwiseAbs().maxCoeff();
    if (!(largest > 0.0)) throw InvalidInput("load '" + load.spec + "': the normal after '^' is zero");
    load.normal = (normal / largest).normalized();
    selection = selection.substr(0, caret);
  }
  load.selection = parse_selection(selection);
  const auto f = parse_number_list(spec.substr(eq + 1), "load '" + load.spec + "': force", 3, "fx,fy,fz (newtons)");
  load.force = Eigen::Vector3d(f[0], f[1], f[2]);
  return load;
}

SelectedRegion loaded_faces(const TetMesh& mesh, const LoadSpec& load) {
  SelectedRegion region = resolve_selection(mesh, load.selection);
  if (region.faces.empty()) {
    throw InvalidInput("load patch '" + load.selection.spec + "' touches no boundary face of " + mesh_name(mesh));
  }
  const std::optional<Eigen::Vector3d> centre = selection_centre(load.selection);
  if (!load.normal && !centre) return region;  // a named surface, loaded whole

  auto face_point = [&](const std::array<int, 3>& f, int k) -> Eigen::Vector3d {
    return mesh.nodes().row(f[static_cast<std::size_t>(k)]).transpose();
  };
  std::vector<Eigen::Vector3d> normals(region.faces.size());
  for (std::size_t k = 0; k < region.faces.size(); ++k) {
    const auto& f = region.faces[k];
    normals[k] = (face_point(f, 1) - face_point(f, 0)).cross(face_point(f, 2) - face_point(f, 0)).normalized();
  }
  Eigen::Vector3d reference;
  if (load.normal) {
    reference = *load.normal;
  } else {
    // The face nearest to the centre (by centroid; the first of equals) sets the side.
    double nearest = INFINITY;
    for (std::size_t k = 0; k < region.faces.size(); ++k) {
      const auto& f = region.faces[k];
      const Eigen::Vector3d centroid = (face_point(f, 0) + face_point(f, 1) + face_point(f, 2)) / 3.0;
      const double distance = (centroid - *centre).squaredNorm();
      if (distance < nearest) {
        nearest = distance;
        reference = normals[k];
      }
    }
  }
  // 0.01 = cos 89.4°: faces at right angles to the reference (the sides of a plate whose edge the
  // ball reaches) are left out even with round-off in their normals.
  SelectedRegion facing;
  for (std::size_t k = 0; k < region.faces.size(); ++k) {
    if (normals[k].dot(reference) > 0.01) {
      facing.faces.push_back(region.faces[k]);
      facing.nodes.insert(facing.nodes.end(), region.faces[k].begin(), region.faces[k].end());
    }
  }
  std::sort(facing.nodes.begin(), facing.nodes.end());
  facing.nodes.erase(std::unique(facing.nodes.begin(), facing.nodes.end()), facing.nodes.end());
  if (facing.faces.empty()) {
    throw InvalidInput("load patch '" + load.selection.spec + "' touches no boundary face of " + mesh_name(mesh) +
                       " facing along the normal " + format_number(reference.x(), 3) + "," +
                       format_number(reference.y(), 3) + "," + format_number(reference.z(), 3));
  }
  return facing;
}

Eigen::VectorXd assemble_load(const TetMesh& mesh, const LoadSpec& load) {
  const SelectedRegion region = loaded_faces(mesh, load);
  const Eigen::VectorXd areas = face_areas(mesh, region);
  const double total_area = areas.sum();
  if (!(total_area > 0.0)) {
    throw InvalidInput("load patch '" + load.selection.spec + "' has zero area on " + mesh_name(mesh));
  }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(mesh.node_count()));
  for (std::size_t k = 0; k < region.faces.size(); ++k) {
    const Eigen::Vector3d per_node = load.force * (areas[static_cast<Eigen::Index>(k)] / total_area / 3.0);
    for (int v : region.faces[k]) f.segment<3>(3 * static_cast<Eigen::Index>(v)) += per_node;
  }
  return f;
}

Eigen::VectorXd gravity_load(const TetMesh& mesh, double density, const Eigen::Vector3d& g) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(mesh.node_count()));
  for (int t = 0; t < mesh.tet_count(); ++t) {
    const Eigen::Vector3d share = g * (density * mesh.volumes()[t] / 4.0);
    for (int a = 0; a < 4; ++a) f.segment<3>(3 * static_cast<Eigen::Index>(mesh.tets()(t, a))) += share;
  }
  return f;
}

}  // namespace fissure
