#include "body_geometry.hpp"

#include <map>
#include <utility>

namespace fissure::studio {
namespace {

void put(std::vector<float>& out, const Eigen::Vector3d& v) {
  out.push_back(static_cast<float>(v.x()));
  out.push_back(static_cast<float>(v.y()));
  out.push_back(static_cast<float>(v.z()));
}

void add_triangle(BodyGeometry& g, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& colour, float crack) {
  Eigen::Vector3d n = (b - a).cross(c - a);
  const double length = n.norm();
  n = length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::UnitZ();  // a sliver still gets drawn
  for (const Eigen::Vector3d* p : {&a, &b, &c}) {
    put(g.surface, *p);
    put(g.surface, n);
    put(g.surface, colour);
    g.surface.push_back(crack);
    g.bounds.extend(*p);
  }
}

int surface_vertices(const BodyGeometry& g) { return static_cast<int>(g.surface.size() / BodyGeometry::kSurfaceFloats); }
int line_vertices(const BodyGeometry& g) { return static_cast<int>(g.lines.size() / BodyGeometry::kLineFloats); }

}  // namespace

Eigen::Vector3d body_colour(const ImportedScene& scene, const SceneBody& body) {
  for (int m : body.meshes) {
    const int material = scene.meshes[static_cast<std::size_t>(m)].material;
    if (material >= 0) return scene.materials[static_cast<std::size_t>(material)].colour;
  }
  return Eigen::Vector3d::Constant(0.8);
}

BodyGeometry whole_body_geometry(const ImportedScene& scene, const SceneBody& body) {
  BodyGeometry g;
  BodyGeometry::Range r;
  for (int m : body.meshes) {
    const SceneMesh& mesh = scene.meshes[static_cast<std::size_t>(m)];
    const Eigen::Vector3d colour = mesh.material >= 0 ? scene.materials[static_cast<std::size_t>(mesh.material)].colour
                                                      : Eigen::Vector3d::Constant(0.8);
    const Eigen::Matrix3d linear = body.world.topLeftCorner<3, 3>();
    const Eigen::Vector3d shift = body.world.topRightCorner<3, 1>();
    // A mirroring transform (negative determinant) turns the winding; keep outward normals.
    const bool mirrored = linear.determinant() < 0.0;
    for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
      Eigen::Vector3d p[3];
      for (int k = 0; k < 3; ++k) p[k] = linear * mesh.vertices.row(mesh.triangles(t, k)).transpose() + shift;
      if (mirrored) std::swap(p[1], p[2]);
      add_triangle(g, p[0], p[1], p[2], colour, 0.0f);
    }
  }
  r.count = surface_vertices(g);
  g.ranges.push_back(r);
  return g;
}

BodyGeometry fragment_geometry(const std::vector<FragmentMesh>& fragments, const Eigen::Vector3d& colour,
                               const Eigen::Vector3d& line_colour, double scale) {
  BodyGeometry g;
  for (std::size_t f = 0; f < fragments.size(); ++f) {
    const FragmentMesh& m = fragments[f];
    BodyGeometry::Range r;
    r.fragment = static_cast<int>(f);
    r.first = surface_vertices(g);
    r.first_line = line_vertices(g);
    // Edges by their vertex pair: an edge between a crack face and an outer face is a crack
    // line as the photograph would show it.
    std::map<std::pair<int, int>, std::pair<int, int>> edge_faces;  // → (crack faces, outer faces)
    for (Eigen::Index t = 0; t < m.triangles.rows(); ++t) {
      const bool crack = t < static_cast<Eigen::Index>(m.triangle_crack.size()) && m.triangle_crack[static_cast<std::size_t>(t)] >= 0;
      add_triangle(g, scale * m.vertices.row(m.triangles(t, 0)).transpose(), scale * m.vertices.row(m.triangles(t, 1)).transpose(),
                   scale * m.vertices.row(m.triangles(t, 2)).transpose(), colour, crack ? 1.0f : 0.0f);
      for (int k = 0; k < 3; ++k) {
        int a = m.triangles(t, k), b = m.triangles(t, (k + 1) % 3);
        if (a > b) std::swap(a, b);
        auto& count = edge_faces[{a, b}];
        (crack ? count.first : count.second) += 1;
      }
    }
    for (const auto& [edge, count] : edge_faces) {
      if (count.first == 0 || count.second == 0) continue;
      put(g.lines, scale * m.vertices.row(edge.first).transpose());
      put(g.lines, line_colour);
      put(g.lines, scale * m.vertices.row(edge.second).transpose());
      put(g.lines, line_colour);
    }
    r.count = surface_vertices(g) - r.first;
    r.line_count = line_vertices(g) - r.first_line;
    g.ranges.push_back(r);
  }
  return g;
}

double ray_hit(const BodyGeometry& g, const BodyGeometry::Range& r, const Eigen::Vector3d& offset,
               const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
  // Möller–Trumbore, both faces (a click hits what it sees, whichever way it is wound).
  double best = -1.0;
  const int stride = BodyGeometry::kSurfaceFloats;
  for (int v = r.first; v + 2 < r.first + r.count; v += 3) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) {
      const float* q = &g.surface[static_cast<std::size_t>((v + k) * stride)];
      p[k] = Eigen::Vector3d(q[0], q[1], q[2]) + offset;
    }
    const Eigen::Vector3d e1 = p[1] - p[0], e2 = p[2] - p[0];
    const Eigen::Vector3d h = direction.cross(e2);
    const double a = e1.dot(h);
    if (std::abs(a) < 1e-300) continue;
    const Eigen::Vector3d s = origin - p[0];
    const double u = s.dot(h) / a;
    if (u < 0.0 || u > 1.0) continue;
    const Eigen::Vector3d q = s.cross(e1);
    const double w = direction.dot(q) / a;
    if (w < 0.0 || u + w > 1.0) continue;
    const double t = e2.dot(q) / a;
    if (t > 0.0 && (best < 0.0 || t < best)) best = t;
  }
  return best;
}

}  // namespace fissure::studio
