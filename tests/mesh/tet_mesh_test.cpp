#include "fissure/base/error.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace fissure {
namespace {

TetMesh unit_tet() {
  Eigen::MatrixX3d nodes(4, 3);
  nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::MatrixX4i tets(1, 4);
  tets << 0, 1, 2, 3;
  return TetMesh(nodes, tets, "unit");
}

// A unit cube split into 6 tets around the diagonal 0–6 (Kuhn triangulation), all positive.
TetMesh kuhn_cube(const Eigen::Vector3d& offset = Eigen::Vector3d::Zero(), double scale = 1.0) {
  Eigen::MatrixX3d nodes(8, 3);
  for (int i = 0; i < 8; ++i) {
    nodes.row(i) = (scale * Eigen::Vector3d(i & 1, (i >> 1) & 1, (i >> 2) & 1) + offset).transpose();
  }
  // Paths from corner 0 to corner 7 through the 6 axis orders.
  const int paths[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                           {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  Eigen::MatrixX4i tets(6, 4);
  for (int t = 0; t < 6; ++t) {
    Eigen::Vector4i tet(paths[t][0], paths[t][1], paths[t][2], paths[t][3]);
    const Eigen::Vector3d a = nodes.row(tet[0]), b = nodes.row(tet[1]), c = nodes.row(tet[2]),
                          d = nodes.row(tet[3]);
    if ((b - a).dot((c - a).cross(d - a)) < 0) std::swap(tet[2], tet[3]);
    tets.row(t) = tet.transpose();
  }
  return TetMesh(nodes, tets, "cube");
}

TEST(TetMesh, UnitTetVolumeAndBoundary) {
  const TetMesh m = unit_tet();
  EXPECT_DOUBLE_EQ(m.volumes()[0], 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(m.total_volume(), 1.0 / 6.0);
  EXPECT_EQ(m.boundary_faces().size(), 4u);
  EXPECT_EQ(m.component_count(), 1);
  EXPECT_TRUE((m.neighbours().array() == -1).all());
  // Outward normals: the divergence theorem gives back the volume, and normals sum to zero.
  double volume = 0.0;
  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
  for (const BoundaryFace& f : m.boundary_faces()) {
    const Eigen::Vector3d a = m.nodes().row(f.nodes[0]), b = m.nodes().row(f.nodes[1]),
                          c = m.nodes().row(f.nodes[2]);
    volume += a.dot(b.cross(c)) / 6.0;
    normal_sum += (b - a).cross(c - a);
  }
  EXPECT_NEAR(volume, 1.0 / 6.0, 1e-15);
  EXPECT_LT(normal_sum.norm(), 1e-15);
}

TEST(TetMesh, CubeAdjacencyBoundaryAndVolume) {
  const TetMesh m = kuhn_cube();
  EXPECT_NEAR(m.total_volume(), 1.0, 1e-14);
  // 6 tets × 4 faces = 24 = 2·interior + boundary; the cube's 6 squares give 12 boundary faces.
  EXPECT_EQ(m.boundary_faces().size(), 12u);
  int interior_links = 0;
  for (int t = 0; t < m.tet_count(); ++t) {
    for (int f = 0; f < 4; ++f) {
      const int n = m.neighbours()(t, f);
      if (n < 0) continue;
      ++interior_links;
      // Symmetry: t is among n's neighbours.
      EXPECT_TRUE((m.neighbours().row(n).array() == t).any());
    }
  }
  EXPECT_EQ(interior_links, 12);
  double volume = 0.0;
  for (const BoundaryFace& f : m.boundary_faces()) {
    const Eigen::Vector3d a = m.nodes().row(f.nodes[0]), b = m.nodes().row(f.nodes[1]),
                          c = m.nodes().row(f.nodes[2]);
    volume += a.dot(b.cross(c)) / 6.0;
  }
  EXPECT_NEAR(volume, 1.0, 1e-14);
}

TEST(TetMesh, ComponentsAreCounted) {
  const TetMesh a = kuhn_cube();
  const TetMesh b = kuhn_cube(Eigen::Vector3d(3, 0, 0));
  Eigen::MatrixX3d nodes(16, 3);
  nodes << a.nodes(), b.nodes();
  Eigen::MatrixX4i tets(12, 4);
  tets << a.tets(), (b.tets().array() + 8).matrix();
  const TetMesh m(nodes, tets, "two cubes");
  EXPECT_EQ(m.component_count(), 2);
  EXPECT_EQ(m.component_of_tet()[0], 0);
  EXPECT_EQ(m.component_of_tet()[11], 1);
  const auto node_component = m.component_of_node();
  EXPECT_EQ(node_component[0], 0);
  EXPECT_EQ(node_component[15], 1);
}

std::string error_of(const Eigen::MatrixX3d& nodes, const Eigen::MatrixX4i& tets) {
  try {
    TetMesh m(nodes, tets, "bad.msh");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(TetMesh, InvertedTetIsAnErrorNamingIt) {
  const TetMesh cube = kuhn_cube();
  Eigen::MatrixX4i tets = cube.tets();
  std::swap(tets(4, 2), tets(4, 3));
  const std::string msg = error_of(cube.nodes(), tets);
  EXPECT_NE(msg.find("bad.msh: tet 4 is inverted"), std::string::npos) << msg;
}

TEST(TetMesh, ZeroVolumeIsAnErrorButASliverIsNot) {
  Eigen::MatrixX3d nodes(4, 3);
  nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, 0.5, 0;  // flat
  Eigen::MatrixX4i tets(1, 4);
  tets << 0, 1, 2, 3;
  EXPECT_NE(error_of(nodes, tets).find("tet 0 has zero volume"), std::string::npos);
  nodes(3, 2) = 1e-6;  // near-flat but real: accepted, and reported by quality()
  const TetMesh sliver(nodes, tets, "sliver");
  const QualityReport q = sliver.quality();
  EXPECT_LT(q.min_dihedral_deg, 0.01);
  EXPECT_EQ(q.sliver_count, 1);
  EXPECT_EQ(q.worst_dihedral_tet, 0);
}

TEST(TetMesh, OtherDefectsAreNamed) {
  Eigen::MatrixX3d nodes(5, 3);
  nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 9, 9, 9;
  Eigen::MatrixX4i tets(1, 4);
  tets << 0, 1, 2, 3;
  EXPECT_NE(error_of(nodes, tets).find("node 4 belongs to no tet"), std::string::npos);
  tets << 0, 1, 2, 7;
  EXPECT_NE(error_of(nodes.topRows(4), tets).find("tet 0 references node 7"), std::string::npos);
  tets << 0, 1, 1, 3;
  EXPECT_NE(error_of(nodes.topRows(4), tets).find("uses node 1 twice"), std::string::npos);
  Eigen::MatrixX3d nan_nodes = nodes.topRows(4);
  nan_nodes(2, 1) = std::nan("");
  tets << 0, 1, 2, 3;
  EXPECT_NE(error_of(nan_nodes, tets).find("node 2 has a non-finite"), std::string::npos);
  EXPECT_NE(error_of(Eigen::MatrixX3d(0, 3), Eigen::MatrixX4i(0, 4)).find("no tetrahedra"),
            std::string::npos);
}

TEST(TetMesh, FaceSharedByThreeTetsIsRefused) {
  Eigen::MatrixX3d nodes(6, 3);
  nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.2, 0.2, -1, 0.3, 0.3, 2;
  Eigen::MatrixX4i tets(3, 4);
  tets << 0, 1, 2, 3,   // above the face (0,1,2)
      0, 2, 1, 4,       // below it
      0, 1, 2, 5;       // above again: face (0,1,2) used three times
  const std::string msg = error_of(nodes, tets);
  EXPECT_NE(msg.find("shared by 3 tets"), std::string::npos) << msg;
}

TEST(TetShape, RegularTetMeasures) {
  const Eigen::Vector3d a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  const TetShape s = tet_shape(a, b, d, c);  // (a, b, d, c) is the positive order
  const double regular_dihedral = std::acos(1.0 / 3.0) * 180.0 / std::numbers::pi;  // 70.5288°
  EXPECT_NEAR(s.min_dihedral_deg, regular_dihedral, 1e-10);
  EXPECT_NEAR(s.max_dihedral_deg, regular_dihedral, 1e-10);
  EXPECT_NEAR(s.radius_ratio, 1.0, 1e-12);
  EXPECT_NEAR(s.radius_edge, std::sqrt(6.0) / 4.0, 1e-12);  // 0.6124
  EXPECT_GT(s.volume, 0.0);
}

TEST(TetShape, RightCornerTet) {
  // Unit corner tet: three 90° dihedrals at the origin edges, and arccos(1/√3) = 54.74° at the
  // slanted face's edges.
  const TetShape s = tet_shape({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  EXPECT_NEAR(s.max_dihedral_deg, 90.0, 1e-10);
  EXPECT_NEAR(s.min_dihedral_deg, std::acos(1.0 / std::sqrt(3.0)) * 180.0 / std::numbers::pi, 1e-10);
  EXPECT_NEAR(s.volume, 1.0 / 6.0, 1e-15);
}

TEST(TetMesh, NamedSetsAreCheckedAndFound) {
  const TetMesh cube = kuhn_cube();
  NamedSet bottom{"bottom", 2, {0, 1, 2, 3}, {{0, 1, 3}, {0, 3, 2}}, {}};
  const TetMesh m(cube.nodes(), cube.tets(), "cube", {bottom});
  ASSERT_NE(m.find_named_set("bottom"), nullptr);
  EXPECT_EQ(m.find_named_set("top"), nullptr);
  NamedSet broken{"broken", 0, {42}, {}, {}};
  EXPECT_THROW(TetMesh(cube.nodes(), cube.tets(), "cube", {broken}), InvalidInput);
}

}  // namespace
}  // namespace fissure
