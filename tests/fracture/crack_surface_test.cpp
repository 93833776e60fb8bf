#include "fissure/fracture/crack_surface.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace fissure {
namespace {

Eigen::Matrix<double, 4, 3> unit_tet() {
  Eigen::Matrix<double, 4, 3> n;
  n << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return n;
}

// Values of the plane x = c at the unit tet's nodes: the P1 interpolant is exact for a plane, so
// the polygon must lie on it.
CrackCut plane_cut(const Eigen::Vector3d& normal, double offset) {
  CrackCut cut;
  const auto n = unit_tet();
  for (int i = 0; i < 4; ++i) cut.node_values[i] = normal.dot(n.row(i).transpose()) - offset;
  return cut;
}

double polygon_area(const std::vector<Eigen::Vector3d>& p) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 1; i + 1 < p.size(); ++i) sum += (p[i] - p[0]).cross(p[i + 1] - p[0]);
  return 0.5 * sum.norm();
}

TEST(CrackPolygon, TriangleAndQuadLieOnThePlane) {
  const auto nodes = unit_tet();
  // x = 0.5 separates node 1 from the rest: a triangle with legs 0.5, area 0.125.
  const auto tri = crack_polygon(nodes, plane_cut(Eigen::Vector3d::UnitX(), 0.5));
  ASSERT_EQ(tri.size(), 3u);
  for (const auto& p : tri) EXPECT_NEAR(p.x(), 0.5, 1e-15);
  EXPECT_NEAR(polygon_area(tri), 0.125, 1e-15);
  // x + y = 0.5 separates nodes {1, 2} from {0, 3}: a quad.
  const Eigen::Vector3d n = Eigen::Vector3d(1, 1, 0).normalized();
  const auto quad = crack_polygon(nodes, plane_cut(n, 0.5 / std::sqrt(2.0)));
  ASSERT_EQ(quad.size(), 4u);
  for (const auto& p : quad) EXPECT_NEAR(p.x() + p.y(), 0.5, 1e-15);
  // The quad goes round: consecutive edges never cross, so its fan area equals the sum of the
  // two triangles' areas either way it is split.
  const double a1 = polygon_area({quad[0], quad[1], quad[2]}) + polygon_area({quad[0], quad[2], quad[3]});
  const double a2 = polygon_area({quad[1], quad[2], quad[3]}) + polygon_area({quad[1], quad[3], quad[0]});
  EXPECT_NEAR(a1, a2, 1e-15);
  // No sign change, no polygon.
  EXPECT_TRUE(crack_polygon(nodes, plane_cut(Eigen::Vector3d::UnitX(), 2.0)).empty());
}

TEST(CrackPolygon, ClippingKeepsTheArrivalSide) {
  const auto nodes = unit_tet();
  CrackCut k = plane_cut(Eigen::Vector3d::UnitX(), 0.2);
  const CrackCut j = plane_cut(Eigen::Vector3d::UnitY(), 0.3);
  k.clipped_by = 0;
  k.clip_side = -1;  // arrived from y < 0.3
  const auto clipped = crack_polygon(nodes, k, &j);
  ASSERT_GE(clipped.size(), 3u);
  for (const auto& p : clipped) {
    EXPECT_NEAR(p.x(), 0.2, 1e-15);
    EXPECT_LE(p.y(), 0.3 + 1e-15);
  }
  k.clip_side = +1;
  const auto other = crack_polygon(nodes, k, &j);
  // The two sides together are the whole polygon.
  EXPECT_NEAR(polygon_area(clipped) + polygon_area(other), polygon_area(crack_polygon(nodes, plane_cut(Eigen::Vector3d::UnitX(), 0.2))),
              1e-15);
}

}  // namespace
}  // namespace fissure
