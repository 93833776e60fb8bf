#include "fissure/fracture/fracture_body.hpp"

#include "fissure/base/error.hpp"
#include "nearest_seed.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace fissure {

FractureBody::FractureBody(std::shared_ptr<const TetMesh> mesh) : m_mesh(std::move(mesh)) {
  if (!m_mesh || m_mesh->tet_count() == 0) throw InvalidInput("fracture body: the mesh has no tetrahedra");
  const TetMesh& m = *m_mesh;
  const auto& faces = m.boundary_faces();
  const auto& nodes = m.nodes();
  std::vector<Eigen::Vector3d> face_centre(faces.size());
  std::vector<std::pair<int, int>> seeds;
  seeds.reserve(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto& f = faces[i];
    face_centre[i] = (nodes.row(f.nodes[0]) + nodes.row(f.nodes[1]) + nodes.row(f.nodes[2])).transpose() / 3.0;
    seeds.emplace_back(f.tet, static_cast<int>(i));
  }
  detail::NearestSeedPropagation propagation(m);
  propagation.run(
      seeds, [&](int tet, int face) { return (m.centroid(tet) - face_centre[static_cast<std::size_t>(face)]).norm(); },
      std::numeric_limits<double>::infinity());

  const auto n = static_cast<Eigen::Index>(m.tet_count());
  m_surface_normals.resize(n, 3);
  m_surface_distances.resize(n);
  m_tangent.resize(n, 6);
  for (Eigen::Index t = 0; t < n; ++t) {
    const int face = propagation.seed_of(static_cast<int>(t));
    // Every tet of a mesh whose components all have a boundary is reached.
    const Eigen::Vector3d nrm = faces[static_cast<std::size_t>(face)].normal;
    m_surface_normals.row(t) = nrm.transpose();
    m_surface_distances(t) = propagation.distance_of(static_cast<int>(t));
    m_tangent.row(t) << 1.0 - nrm.x() * nrm.x(), 1.0 - nrm.y() * nrm.y(), 1.0 - nrm.z() * nrm.z(), -nrm.y() * nrm.z(),
        -nrm.x() * nrm.z(), -nrm.x() * nrm.y();
  }

  // Mean edge length over the six edges of every tet (interior edges counted once per tet that
  // holds them: a volume-weighted-ish mean, stable and cheap). Summed in fixed point, in units of
  // 2⁻³² of the bounding box's diagonal (an edge is at most 2³² units; 3·10⁸ tets fit in 63 bits),
  // so the sum is exact and the same bits in any tet order: crack paths step by it, and a
  // renumbered mesh must fracture the same (ElementOrder tests).
  const auto box = m.bounding_box();
  const double unit = (box.row(1) - box.row(0)).norm() * 0x1p-32;
  std::int64_t sum = 0;
  const auto& tets = m.tets();
  for (Eigen::Index t = 0; t < n; ++t) {
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) sum += std::llround((nodes.row(tets(t, a)) - nodes.row(tets(t, b))).norm() / unit);
    }
  }
  m_mean_edge = static_cast<double>(sum) * unit / (6.0 * static_cast<double>(n));
}

}  // namespace fissure
