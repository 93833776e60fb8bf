#include "fissure/fem/selection.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <set>

namespace fissure {
Selection parse_selection(std::string_view spec) {
  Selection s;
  s.spec = std::string(spec);
  if (spec.empty()) throw InvalidInput("selection: empty selection spec");
  if (spec.starts_with("box:")) {
    const auto v = parse_number_list(spec.substr(4), "selection '" + s.spec + "': box", 6, "x0,x1,y0,y1,z0,z1");
    for (int axis = 0; axis < 3; ++axis) {
      if (v[2 * axis] > v[2 * axis + 1]) {
        throw InvalidInput("selection '" + s.spec + "': box bound " + "xyz"[axis] +
                           "0 is larger than " + "xyz"[axis] + "1");
      }
    }
    s.kind = Selection::Kind::Box;
    for (int i = 0; i < 6; ++i) s.box[i] = v[i];
  } else if (spec.starts_with("ball:")) {
    const auto v = parse_number_list(spec.substr(5), "selection '" + s.spec + "': ball", 4, "x,y,z,r");
    if (v[3] <= 0.0) throw InvalidInput("selection '" + s.spec + "': ball radius must be positive");
    s.kind = Selection::Kind::Ball;
    s.center = Eigen::Vector3d(v[0], v[1], v[2]);
    s.radius = v[3];
  } else {
    if (spec.find_first_of(":=,^ \t") != std::string_view::npos) {
      throw InvalidInput("selection '" + s.spec +
                         "': expected box:x0,x1,y0,y1,z0,z1, ball:x,y,z,r or a physical group name");
    }
    s.kind = Selection::Kind::NamedSet;
    s.name = s.spec;
  }
  return s;
}

SelectedRegion resolve_selection(const TetMesh& mesh, const Selection& selection) {
  SelectedRegion region;
  const auto& x = mesh.nodes();
  const auto box = mesh.bounding_box();
  const double tolerance = 1e-9 * (box.row(1) - box.row(0)).norm();

  if (selection.kind == Selection::Kind::NamedSet) {
    const NamedSet* set = mesh.find_named_set(selection.name);
    if (!set) {
      std::string known;
      for (const NamedSet& s : mesh.named_sets()) known += (known.empty() ? "" : ", ") + s.name;
      throw InvalidInput("selection '" + selection.spec + "': the mesh has no physical group of that name" +
                         (known.empty() ? std::string(" (it has none)") : " (it has: " + known + ")"));
    }
    region.nodes = set->nodes;
    std::sort(region.nodes.begin(), region.nodes.end());
    region.nodes.erase(std::unique(region.nodes.begin(), region.nodes.end()), region.nodes.end());
    if (set->dimension == 2 && !set->faces.empty()) {
      // Use the set's own triangles, wound as the mesh boundary winds them when they lie on it.
      std::set<std::array<int, 3>> wanted;
      for (auto f : set->faces) {
        std::sort(f.begin(), f.end());
        wanted.insert(f);
      }
      for (const BoundaryFace& bf : mesh.boundary_faces()) {
        auto key = bf.nodes;
        std::sort(key.begin(), key.end());
        if (wanted.count(key)) region.faces.push_back(bf.nodes);
      }
      return region;
    }
  } else {
    for (int v = 0; v < mesh.node_count(); ++v) {
      const Eigen::Vector3d p = x.row(v);
      bool inside;
      if (selection.kind == Selection::Kind::Box) {
        inside = true;
        for (int axis = 0; axis < 3; ++axis) {
          inside = inside && p[axis] >= selection.box[2 * axis] - tolerance &&
                   p[axis] <= selection.box[2 * axis + 1] + tolerance;
        }
      } else {
        inside = (p - selection.center).norm() <= selection.radius + tolerance;
      }
      if (inside) region.nodes.push_back(v);
    }
  }

  std::vector<char> selected(static_cast<std::size_t>(mesh.node_count()), 0);
  for (int v : region.nodes) selected[static_cast<std::size_t>(v)] = 1;
  for (const BoundaryFace& bf : mesh.boundary_faces()) {
    if (selected[bf.nodes[0]] && selected[bf.nodes[1]] && selected[bf.nodes[2]]) {
      region.faces.push_back(bf.nodes);
    }
  }
  return region;
}

Eigen::VectorXd face_areas(const TetMesh& mesh, const SelectedRegion& region) {
  Eigen::VectorXd areas(static_cast<Eigen::Index>(region.faces.size()));
  for (std::size_t f = 0; f < region.faces.size(); ++f) {
    const Eigen::Vector3d a = mesh.nodes().row(region.faces[f][0]);
    const Eigen::Vector3d b = mesh.nodes().row(region.faces[f][1]);
    const Eigen::Vector3d c = mesh.nodes().row(region.faces[f][2]);
    areas[static_cast<Eigen::Index>(f)] = 0.5 * (b - a).cross(c - a).norm();
  }
  return areas;
}

}  // namespace fissure
