#include "fissure/base/error.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

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
  // Named by its 1-based tag, as gmsh shows it (the 0-based "tet 4" was gmsh's element 5).
  EXPECT_NE(msg.find("bad.msh: tet 5 is inverted"), std::string::npos) << msg;
}

TEST(TetMesh, ZeroVolumeIsAnErrorButASliverIsNot) {
  Eigen::MatrixX3d nodes(4, 3);
  nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, 0.5, 0;  // flat
  Eigen::MatrixX4i tets(1, 4);
  tets << 0, 1, 2, 3;
  EXPECT_NE(error_of(nodes, tets).find("tet 1 has zero volume"), std::string::npos);
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
  EXPECT_NE(error_of(nodes, tets).find("node 5 belongs to no tet"), std::string::npos);
  tets << 0, 1, 2, 7;
  EXPECT_NE(error_of(nodes.topRows(4), tets).find("tet 1 references node index 7"), std::string::npos);
  tets << 0, 1, 1, 3;
  EXPECT_NE(error_of(nodes.topRows(4), tets).find("uses node 2 twice"), std::string::npos);
  Eigen::MatrixX3d nan_nodes = nodes.topRows(4);
  nan_nodes(2, 1) = std::nan("");
  tets << 0, 1, 2, 3;
  EXPECT_NE(error_of(nan_nodes, tets).find("node 3 has a non-finite"), std::string::npos);
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


// A file's own tags name the culprit: gmsh shows element 1203, not Fissure's index.
TEST(TetMesh, MessagesUseTheFilesTags) {
  const TetMesh cube = kuhn_cube();
  Eigen::MatrixX4i tets = cube.tets();
  std::swap(tets(2, 2), tets(2, 3));
  EntityTags tags;
  tags.nodes = {11, 12, 13, 14, 15, 16, 17, 18};
  tags.tets = {1201, 1202, 1203, 1204, 1205, 1206};
  try {
    TetMesh m(cube.nodes(), tets, "tagged.msh", {}, tags);
    FAIL() << "inverted tet accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("tagged.msh: tet 1203 is inverted"), std::string::npos) << e.what();
  }
  const TetMesh ok(cube.nodes(), cube.tets(), "tagged.msh", {}, tags);
  EXPECT_EQ(ok.node_tag(0), 11);
  EXPECT_EQ(ok.tet_label(5), "tet 1206");
  EXPECT_EQ(kuhn_cube().node_label(7), "node 8");
  // Scale does not matter to the checks: a cube of 1e-100 m once read as folded (its angles
  // underflowed to zero).
  EXPECT_NO_THROW(kuhn_cube(Eigen::Vector3d::Zero(), 1e-100));
  EXPECT_NO_THROW(kuhn_cube(Eigen::Vector3d::Constant(1e6), 1e3));
  tags.tets.pop_back();
  EXPECT_THROW(TetMesh(cube.nodes(), cube.tets(), "tagged.msh", {}, tags), InvalidInput);
}

// Two tets on the same side of a shared face overlap; the old face pairing only counted tets
// per face, so the volume was counted twice.
TEST(TetMesh, StackedAndDuplicatedTetsAreRefused) {
  Eigen::MatrixX3d nodes(5, 3);
  nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.2, 0.2, 0.5;
  Eigen::MatrixX4i tets(2, 4);
  tets << 0, 1, 2, 3,  // above face (0, 1, 2)
      0, 1, 2, 4;      // above it too: overlaps the first
  std::string msg = error_of(nodes, tets);
  EXPECT_NE(msg.find("tet 1 and tet 2 overlap"), std::string::npos) << msg;
  EXPECT_NE(msg.find("same side of face (node 1, 2, 3)"), std::string::npos) << msg;
  tets << 0, 1, 2, 3, 1, 2, 0, 3;  // the same tet twice, its nodes rotated
  msg = error_of(nodes.topRows(4), tets);
  EXPECT_NE(msg.find("tet 1 and tet 2 are the same tet"), std::string::npos) << msg;
}

// A fan of tets wound twice around an interior edge: every face has one tet on either side,
// yet the tets cover the space around the edge twice. The dihedral angles there sum to 720°.
TEST(TetMesh, MeshFoldedAroundAnEdgeIsRefused) {
  const int ring = 8;  // nodes around the axis; the fan goes round twice through them
  Eigen::MatrixX3d nodes(2 + ring, 3);
  nodes.row(0) << 0, 0, -1;
  nodes.row(1) << 0, 0, 1;
  for (int k = 0; k < ring; ++k) {
    const double phi = 2.0 * std::numbers::pi * k / ring;
    nodes.row(2 + k) << std::cos(phi), std::sin(phi), 0.0;
  }
  auto fan = [&](int wraps) {
    std::vector<Eigen::Vector4i> list;
    // Steps of 2 ring nodes (90°) wrap once in 4 tets; steps of 3 (135°) wrap 3 times in 8.
    const int step = wraps == 1 ? 2 : 3;
    int k = 0;
    do {
      const int next = (k + step) % ring;
      Eigen::Vector4i t(0, 1, 2 + k, 2 + next);
      const Eigen::Vector3d a = nodes.row(t[0]), b = nodes.row(t[1]), c = nodes.row(t[2]), d = nodes.row(t[3]);
      if ((b - a).dot((c - a).cross(d - a)) < 0) std::swap(t[2], t[3]);
      list.push_back(t);
      k = next;
    } while (k != 0);
    Eigen::MatrixX4i tets(static_cast<Eigen::Index>(list.size()), 4);
    for (std::size_t i = 0; i < list.size(); ++i) tets.row(static_cast<Eigen::Index>(i)) = list[i].transpose();
    return tets;
  };
  // Once round: a valid octahedron-like fan (only the nodes it uses are kept).
  {
    const Eigen::MatrixX4i tets = fan(1);
    Eigen::MatrixX3d used(6, 3);
    used << nodes.row(0), nodes.row(1), nodes.row(2), nodes.row(4), nodes.row(6), nodes.row(8);
    Eigen::MatrixX4i renumbered = tets;
    for (Eigen::Index i = 0; i < tets.size(); ++i) {
      const int v = tets.data()[i];
      renumbered.data()[i] = v < 2 ? v : 2 + (v - 2) / 2;
    }
    EXPECT_EQ(error_of(used, renumbered), "");
  }
  const std::string msg = error_of(nodes, fan(3));
  EXPECT_NE(msg.find("tets overlap around the edge (node 1, 2)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("sum to 1080 deg"), std::string::npos) << msg;
}

TEST(TetMesh, SeamsForTheFractureStage) {
  const TetMesh m = kuhn_cube();
  // Centroids.
  for (int t = 0; t < m.tet_count(); ++t) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) c += m.nodes().row(m.tets()(t, k)).transpose() / 4.0;
    EXPECT_LT((m.centroid(t) - c).norm(), 1e-15);
  }
  // Neighbour faces are the same triangle, and crossing back returns to the start.
  std::set<int> ids;
  for (int t = 0; t < m.tet_count(); ++t) {
    for (int f = 0; f < 4; ++f) {
      ids.insert(m.face_ids()(t, f));
      const int n = m.neighbours()(t, f);
      if (n < 0) {
        EXPECT_EQ(m.neighbour_faces()(t, f), -1);
        continue;
      }
      const int g = m.neighbour_faces()(t, f);
      ASSERT_GE(g, 0);
      std::array<int, 3> mine{}, theirs{};
      for (int k = 0; k < 3; ++k) {
        mine[k] = m.tets()(t, TetMesh::kLocalFaces[f][k]);
        theirs[k] = m.tets()(n, TetMesh::kLocalFaces[g][k]);
      }
      std::sort(mine.begin(), mine.end());
      std::sort(theirs.begin(), theirs.end());
      EXPECT_EQ(mine, theirs);
      EXPECT_EQ(m.neighbours()(n, g), t);
      EXPECT_EQ(m.neighbour_faces()(n, g), f);
      EXPECT_EQ(m.face_ids()(n, g), m.face_ids()(t, f));
    }
  }
  // 6 interior + 12 boundary triangles, ids 0..17.
  EXPECT_EQ(m.face_count(), 18);
  EXPECT_EQ(ids.size(), 18u);
  EXPECT_EQ(*ids.begin(), 0);
  EXPECT_EQ(*ids.rbegin(), 17);
  // Node → tet incidence: every corner of the Kuhn cube sees its tets; corners 0 and 7 see all 6.
  int total = 0;
  for (int v = 0; v < m.node_count(); ++v) {
    total += m.node_tets().size(v);
    for (const int* t = m.node_tets().begin(v); t != m.node_tets().end(v); ++t) {
      EXPECT_TRUE((m.tets().row(*t).array() == v).any());
      if (t + 1 != m.node_tets().end(v)) {
        EXPECT_LT(*t, *(t + 1));
      }
    }
  }
  EXPECT_EQ(total, 24);
  EXPECT_EQ(m.node_tets().size(0), 6);
  EXPECT_EQ(m.node_tets().size(7), 6);
  // Boundary faces: unit outward normals on the cube's sides, areas 1/2, summing to 6.
  double area = 0.0;
  for (const BoundaryFace& f : m.boundary_faces()) {
    area += f.area;
    EXPECT_NEAR(f.area, 0.5, 1e-15);
    EXPECT_NEAR(f.normal.norm(), 1.0, 1e-15);
    EXPECT_NEAR(f.normal.cwiseAbs().maxCoeff(), 1.0, 1e-15);  // axis-aligned
    const Eigen::Vector3d centre = (m.nodes().row(f.nodes[0]) + m.nodes().row(f.nodes[1]) + m.nodes().row(f.nodes[2])).transpose() / 3.0;
    EXPECT_GT(f.normal.dot(centre - Eigen::Vector3d::Constant(0.5)), 0.0);  // points away from the centre
  }
  EXPECT_NEAR(area, 6.0, 1e-14);
}

}  // namespace
}  // namespace fissure
