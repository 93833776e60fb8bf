#include "fissure/mesh/surface_mesh.hpp"

#include <gtest/gtest.h>

namespace fissure {
namespace {

TEST(SurfaceMesh, UnitTetVolumeAndArea) {
  SurfaceMesh s;
  s.vertices.resize(4, 3);
  s.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  s.faces.resize(4, 3);
  s.faces << 1, 2, 3, 0, 3, 2, 0, 1, 3, 0, 2, 1;
  EXPECT_NEAR(signed_volume(s), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(surface_area(s), 1.5 + std::sqrt(3.0) / 2.0, 1e-14);
  s.faces.col(1).swap(s.faces.col(2));  // inside out
  EXPECT_NEAR(signed_volume(s), -1.0 / 6.0, 1e-15);
}

}  // namespace
}  // namespace fissure
