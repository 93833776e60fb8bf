// The crack texture (crack_texture.hpp): the lines where the fragments' outer faces meet crack
// faces, drawn at the body's UVs. Checked on a slab whose UVs are its top view (u = x, v = y) cut
// by two known planes: the mask is lit along their traces and dark away from them.
#include "fissure/scene/crack_texture.hpp"

#include "../fracture/synthetic_cracks.hpp"
#include "fissure/base/error.hpp"
#include "fissure/mesh/structured_box.hpp"

#include <gtest/gtest.h>

namespace fissure {
namespace {

// The slab's surface as an appearance whose UVs are its top view, one material.
SurfaceAppearance top_view_appearance(const TetMesh& mesh) {
  SurfaceAppearance a;
  a.materials = {{"stone", Eigen::Vector3d::Constant(0.5)}};
  const auto& faces = mesh.boundary_faces();
  a.corners.resize(static_cast<Eigen::Index>(faces.size()), 9);
  a.uvs.resize(static_cast<Eigen::Index>(faces.size()), 6);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d x = mesh.nodes().row(faces[f].nodes[static_cast<std::size_t>(k)]).transpose();
      a.corners.row(static_cast<Eigen::Index>(f)).segment<3>(3 * k) = x.transpose();
      a.uvs.row(static_cast<Eigen::Index>(f)).segment<2>(2 * k) << x.x(), x.y();
    }
    a.material.push_back(0);
  }
  return a;
}

TEST(CrackTexture, LinesLieOnTheCracksTracesInUvSpace) {
  const TetMesh mesh = make_structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 1, 0.1), 8, 8, 1);
  std::vector<CrackSurface> cracks;
  // x = 0.55 through the slab; y = 0.3 ending on it, on the x > 0.55 side only (a T).
  test::add_plane_crack(mesh, cracks, {Eigen::Vector3d::UnitX(), Eigen::Vector3d(0.55, 0.5, 0.05)});
  test::add_plane_crack(mesh, cracks, {Eigen::Vector3d::UnitY(), Eigen::Vector3d(0.8, 0.3, 0.05), {0}});
  const std::vector<FragmentMesh> fragments = mesh_fragments(mesh, cracks, 2);
  ASSERT_EQ(fragments.size(), 3u);
  const SurfaceAppearance appearance = top_view_appearance(mesh);
  CrackTextureOptions options;
  options.size = 256;
  const GreyImage image = crack_texture(fragments, appearance, options);
  ASSERT_EQ(image.width, 256);
  ASSERT_EQ(image.height, 256);
  const auto at = [&](int row, int column) { return image.pixels[static_cast<std::size_t>(row * 256 + column)]; };
  // Pixel column 140 holds u = 0.55 (140.8 px), row 179 holds v = 0.3 ((1 − 0.3)·256 = 179.2 px),
  // each within 0.3 px of the pixels' centres: a 3 px line covers them fully.
  for (int row = 4; row < 252; ++row) EXPECT_EQ(at(row, 140), 255) << "row " << row;
  for (int column = 146; column < 252; ++column) EXPECT_EQ(at(179, column), 255) << "column " << column;
  // The T's stem does not cross to x < 0.55, and nothing is drawn away from the traces.
  for (int column = 4; column < 134; ++column) EXPECT_EQ(at(179, column), 0) << "column " << column;
  for (const auto& [row, column] : {std::pair{64, 64}, {64, 200}, {220, 64}, {230, 200}}) EXPECT_EQ(at(row, column), 0);

  // Same input, same bytes; no UVs, no image; absurd options refused.
  EXPECT_EQ(crack_texture(fragments, appearance, options).pixels, image.pixels);
  SurfaceAppearance plain = appearance;
  plain.uvs.resize(0, 6);
  EXPECT_EQ(crack_texture(fragments, plain, options).width, 0);
  options.size = 8;
  EXPECT_THROW(crack_texture(fragments, appearance, options), InvalidInput);
  options.size = 256;
  options.line_width_px = 0.0;
  EXPECT_THROW(crack_texture(fragments, appearance, options), InvalidInput);
}

}  // namespace
}  // namespace fissure
