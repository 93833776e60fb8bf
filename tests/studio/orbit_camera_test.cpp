#include "orbit_camera.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace fissure::studio {
namespace {

Eigen::Vector3d ndc(const OrbitCamera& c, const Eigen::Vector3d& p, double aspect) {
  const Eigen::Vector4f h = c.projection(aspect) * c.view() * Eigen::Vector4f(p.x(), p.y(), p.z(), 1.0f);
  return Eigen::Vector3d(h.x() / h.w(), h.y() / h.w(), h.z() / h.w());
}

// Framing a box puts all eight corners inside the view and the box centre at the view centre,
// for a wide and a tall window, whatever the camera looked at before.
TEST(OrbitCamera, FramingABoxShowsAllOfIt) {
  for (double aspect : {1.6, 0.5}) {
    OrbitCamera c(Eigen::Vector3d::UnitY());
    c.orbit(1.0, 0.3);
    const Eigen::Vector3d lo(-3, 0, 1), hi(5, 0.2, 2);
    c.frame(lo, hi, aspect);
    const Eigen::Vector3d centre = ndc(c, 0.5 * (lo + hi), aspect);
    EXPECT_NEAR(centre.x(), 0.0, 1e-5);
    EXPECT_NEAR(centre.y(), 0.0, 1e-5);
    double extent = 0.0;
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d corner((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
      const Eigen::Vector3d p = ndc(c, corner, aspect);
      EXPECT_LT(std::abs(p.x()), 1.0) << aspect;
      EXPECT_LT(std::abs(p.y()), 1.0) << aspect;
      EXPECT_GT(p.z(), -1.0);
      EXPECT_LT(p.z(), 1.0);
      extent = std::max({extent, std::abs(p.x()), std::abs(p.y())});
    }
    // …and fills a fair part of it (the bounding sphere, with a 10 % margin, fits the view).
    EXPECT_GT(extent, 0.3) << aspect;
  }
}

// The ray through a pixel passes through the point drawn at that pixel.
TEST(OrbitCamera, APixelsRayMeetsWhatIsDrawnThere) {
  OrbitCamera c(Eigen::Vector3d::UnitZ());
  c.frame(Eigen::Vector3d(-1, -1, 0), Eigen::Vector3d(1, 1, 0.1), 1.5);
  c.orbit(0.4, -0.2);
  const double w = 900, h = 600;
  const Eigen::Vector3d p(0.3, -0.4, 0.05);
  const Eigen::Vector3d n = ndc(c, p, w / h);
  const double x = (n.x() + 1.0) * 0.5 * w - 0.5, y = (1.0 - n.y()) * 0.5 * h - 0.5;
  Eigen::Vector3d origin, direction;
  c.ray(x, y, w, h, origin, direction);
  const Eigen::Vector3d to_p = p - origin;
  // Float32 matrices: the projected pixel is good to ~1e-6 of the view's size.
  EXPECT_LT((to_p - to_p.dot(direction) * direction).norm(), 1e-4 * c.distance());
}

// Orbiting keeps the distance to the target and never flips over the pole; a pan of the view's
// height in pixels moves the target by the view's height at the target's depth.
TEST(OrbitCamera, OrbitKeepsDistanceAndPanFollowsTheCursor) {
  OrbitCamera c(Eigen::Vector3d::UnitY());
  c.frame(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1), 1.0);
  const double d = c.distance();
  c.orbit(0.3, 10.0);  // far past the pole
  EXPECT_NEAR((c.eye() - c.target()).norm(), d, 1e-9 * d);
  EXPECT_GT(c.forward().dot(-Eigen::Vector3d::UnitY()), 0.99);  // looking straight down, not flipped
  const Eigen::Vector3d before = c.target();
  c.pan(0.0, 600.0, 600.0);
  EXPECT_NEAR((c.target() - before).norm(), 2.0 * d * std::tan(0.5 * OrbitCamera::kFieldOfView), 1e-9 * d);
  c.zoom(1.0);
  EXPECT_NEAR(c.distance(), d / 1.2, 1e-12 * d);
}

}  // namespace
}  // namespace fissure::studio
