// The traced course of a turning crack (src/fracture/crack_path.hpp): a straight course is the
// paper's plane, a turning one bends no tighter than its minimum radius and ends where the body
// or an earlier crack does, and its function is one continuous field across the bend.
#include "crack_path.hpp"

#include "fissure/fracture/fracture_body.hpp"
#include "fissure/mesh/structured_box.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <memory>

namespace fissure {
namespace {

using detail::CrackPath;

// A 1 × 1 × 0.02 m plate centred on the origin in x and y, 2.5 cm cells.
struct Plate {
  std::shared_ptr<const TetMesh> mesh =
      std::make_shared<const TetMesh>(make_structured_box({-0.5, -0.5, 0.0}, {1.0, 1.0, 0.02}, 40, 40, 1));
  FractureBody body{mesh};
  int tet_at(const Eigen::Vector3d& x) const {
    int best = 0;
    for (int t = 1; t < mesh->tet_count(); ++t)
      if ((mesh->centroid(t) - x).squaredNorm() < (mesh->centroid(best) - x).squaredNorm()) best = t;
    return best;
  }
};

CrackPath::Options options(double min_radius) {
  CrackPath::Options o;
  o.step = 0.01;
  o.max_length = 1.5;
  o.min_radius = min_radius;
  return o;
}

// No turning: D is the signed distance to the plane through the origin with the crack normal,
// everywhere (beyond the path's ends its end segments go on as rays on that plane), and both
// arms run to the plate's edges.
TEST(CrackPath, AStraightCourseIsThePapersPlane) {
  const Plate plate;
  const Eigen::Vector3d origin = plate.mesh->centroid(plate.tet_at({0.013, -0.02, 0.01}));
  const Eigen::Vector3d normal = Eigen::Vector3d(1.0, 0.4, 0.0).normalized();
  const CrackPath path(*plate.mesh, plate.body.surface_normals(), plate.tet_at(origin), origin, normal, options(0.04),
                       [](int, int, const Eigen::Vector3d& n, const Eigen::Vector3d&, double) { return n; });
  // 1.08 m of course across the plate in 1 cm steps (to within a step at each edge).
  EXPECT_NEAR(0.01 * static_cast<double>(path.points().size() - 1), 1.077, 0.021);
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.3, 0.1, 0.0), Eigen::Vector3d(-0.45, 0.4, 0.02),
                                   Eigen::Vector3d(0.49, -0.49, 0.01), Eigen::Vector3d(2.0, 3.0, 0.0)}) {
    // Round-off of a hundred steps of 1 cm: far below any tet.
    EXPECT_NEAR(path(x), normal.dot(x - origin), 1e-12) << x.transpose();
  }
}

// A course that wants to turn 90° at once bends no tighter than its minimum radius, ends up on
// the wanted normal, and D vanishes on the course and changes continuously across the bend.
TEST(CrackPath, ATurningCourseBendsNoTighterThanItsRadius) {
  const Plate plate;
  const Eigen::Vector3d origin = plate.mesh->centroid(plate.tet_at({-0.3, 0.0, 0.01}));
  const Eigen::Vector3d target = Eigen::Vector3d::UnitY();
  const double radius = 0.05;
  const CrackPath path(*plate.mesh, plate.body.surface_normals(), plate.tet_at(origin), origin, Eigen::Vector3d::UnitX(),
                       options(radius), [&](int, int, const Eigen::Vector3d&, const Eigen::Vector3d&, double) { return target; });
  const auto& p = path.points();
  ASSERT_GE(p.size(), 20u);
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    const Eigen::Vector3d a = (p[i] - p[i - 1]).normalized(), b = (p[i + 1] - p[i]).normalized();
    // The turn per 1 cm step is at most step / radius = 0.2 rad (round-off aside).
    EXPECT_LE(std::acos(std::clamp(a.dot(b), -1.0, 1.0)), 0.01 / radius + 1e-9) << "at point " << i;
    EXPECT_NEAR(path(p[i]), 0.0, 1e-12) << "at point " << i;
  }
  // Both ends run along x once turned (the crack normal is y): the course is an arc into a line.
  EXPECT_NEAR(std::abs((p.back() - p[p.size() - 2]).normalized().x()), 1.0, 1e-9);
  EXPECT_NEAR(std::abs((p[1] - p[0]).normalized().x()), 1.0, 1e-9);
  // Continuity: D sampled along a line across the bend, within the bend radius of the course
  // (beyond it, on the inner side, the nearest point jumps: crack_path.hpp), has no jump larger
  // than its slope times the 1 mm spacing; the slope is 1 plus what the normal's interpolation
  // along a segment adds at 3 cm from the course (≤ 3 cm × 0.2 rad / 1 cm), so 1.6 bounds it.
  const Eigen::Vector3d bend = p[p.size() / 2];
  double previous = path(bend + Eigen::Vector3d(-0.03, -0.03, 0.0) / std::sqrt(2.0));
  for (int i = 1; i <= 60; ++i) {
    const Eigen::Vector3d x = bend + Eigen::Vector3d(-0.03 + 0.001 * i, -0.03 + 0.001 * i, 0.0) / std::sqrt(2.0);
    const double value = path(x);
    EXPECT_LE(std::abs(value - previous), 1.6 * 0.001) << x.transpose();
    previous = value;
  }
}

// An arm ends a few steps after it enters a tet where it may end (an earlier crack), not at the
// edge of the body, and a course along the surface normal (a crack parallel to the surface) is
// the plane.
TEST(CrackPath, ArmsEndAtEarlierCracksAndFlatCracksStayPlanes) {
  const Plate plate;
  const Eigen::Vector3d origin = plate.mesh->centroid(plate.tet_at({0.0, 0.0, 0.01}));
  CrackPath::Options o = options(0.04);
  o.ends_at = [&](int tet) { return std::abs(plate.mesh->centroid(tet).y()) > 0.2; };  // "cracks" at |y| = 0.2
  const CrackPath path(*plate.mesh, plate.body.surface_normals(), plate.tet_at(origin), origin, Eigen::Vector3d::UnitX(),
                       o, [](int, int, const Eigen::Vector3d& n, const Eigen::Vector3d&, double) { return n; });
  for (const Eigen::Vector3d& x : path.points()) EXPECT_LT(std::abs(x.y()), 0.2 + 0.0125 + 0.045) << x.transpose();
  EXPECT_GT(std::abs(path.points().front().y()), 0.2);
  EXPECT_GT(std::abs(path.points().back().y()), 0.2);

  const CrackPath flat(*plate.mesh, plate.body.surface_normals(), plate.tet_at(origin), origin, Eigen::Vector3d::UnitZ(),
                       options(0.04), [](int, int, const Eigen::Vector3d&, const Eigen::Vector3d&, double) {
                         return Eigen::Vector3d(Eigen::Vector3d::UnitX());
                       });
  EXPECT_EQ(flat.points().size(), 1u);
  EXPECT_DOUBLE_EQ(flat(Eigen::Vector3d(0.3, 0.2, 0.015)), 0.015 - origin.z());
}

// A star crack's kinked course (docs/fracture.md, "Star cracks"): arms leaving the origin 120°
// apart, each with its own normal. D vanishes along both arms, is negative inside the 120° wedge
// between them and positive outside it, where the star's third arm runs, and changes
// continuously across the wedge's bisector, where the nearest point switches arms.
TEST(CrackPath, AKinkedCourseIsZeroAlongBothArmsAndSignedByItsWedge) {
  const Plate plate;
  const int origin_tet = plate.tet_at({0.0, 0.0, 0.01});
  const Eigen::Vector3d origin = plate.mesh->centroid(origin_tet);
  // The nearest surface's normal, which the path runs along (the top's or the bottom's): headings
  // turn about it.
  const Eigen::Vector3d up = plate.body.surface_normals().row(origin_tet).transpose();
  const double third = 0.3;  // the third arm's heading, radians from x
  const auto heading = [&](double a) {
    return Eigen::Vector3d(std::cos(a) * Eigen::Vector3d::UnitX() + std::sin(a) * up.cross(Eigen::Vector3d::UnitX()));
  };
  const double kPi = std::acos(-1.0);
  const Eigen::Vector3d minus_arm = heading(third + 2.0 * kPi / 3.0), plus_arm = heading(third - 2.0 * kPi / 3.0);
  ASSERT_NEAR(std::abs(up.z()), 1.0, 1e-12);
  const CrackPath path(*plate.mesh, plate.body.surface_normals(), origin_tet, origin, minus_arm.cross(up),
                       up.cross(plus_arm), options(0.04),
                       [](int, int, const Eigen::Vector3d& n, const Eigen::Vector3d&, double) { return n; });
  for (double s : {0.02, 0.1, 0.3}) {
    // Round-off of up to 30 steps of 1 cm.
    EXPECT_NEAR(path(origin + s * minus_arm), 0.0, 1e-12) << s;
    EXPECT_NEAR(path(origin + s * plus_arm), 0.0, 1e-12) << s;
    // Inside, on the bisector: minus the distance to either arm.
    EXPECT_NEAR(path(origin - s * heading(third)), -s * std::sin(kPi / 3.0), 1e-12) << s;
    // Outside, along the third arm, the nearest point is the kink itself and D is the distance
    // along the minus arm's normal, 30° off the third arm: positive, with no zero to cut.
    EXPECT_NEAR(path(origin + s * heading(third)), s * std::cos(kPi / 6.0), 1e-12) << s;
  }
  // Within the first step of each arm, D is the distance to that arm along its own normal, not
  // blended with the other arm's (the kink keeps both normals up to the origin).
  EXPECT_NEAR(path(origin + 0.005 * plus_arm + 0.003 * up.cross(plus_arm)), 0.003, 1e-12);
  EXPECT_NEAR(path(origin + 0.005 * minus_arm + 0.003 * minus_arm.cross(up)), 0.003, 1e-12);
  // Across the bisector inside the wedge the two arms' distances agree: no jump.
  const Eigen::Vector3d across = up.cross(heading(third));
  const Eigen::Vector3d inside = origin - 0.1 * heading(third);
  EXPECT_NEAR(path(inside + 1e-6 * across), path(inside - 1e-6 * across), 1e-5);
}

}  // namespace
}  // namespace fissure
