// PLY holds one mesh: every part's triangles in one binary file, each vertex tagged with its
// part's index and each face with its material, so a reader can split them again.
#include "scene_encoders.hpp"

#include <cstdint>

namespace fissure::io_detail {

std::string encode_ply(const ExportScene& scene, const Eigen::Matrix3d& turn) {
  std::size_t vertices = 0, faces = 0;
  for (const ExportPart& p : scene.parts) {
    vertices += static_cast<std::size_t>(p.vertices.rows());
    faces += static_cast<std::size_t>(p.triangles.rows());
  }
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment Fissure: metres, +z up; part = index of the fragment\n";
  for (std::size_t m = 0; m < scene.materials.size(); ++m)
    out += "comment material " + std::to_string(m) + " " + scene.materials[m].name + "\n";
  out += "element vertex " + std::to_string(vertices) +
         "\nproperty float x\nproperty float y\nproperty float z\nproperty float s\nproperty float t\nproperty int part\n";
  out += "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\nproperty uchar material\nend_header\n";
  for (std::size_t k = 0; k < scene.parts.size(); ++k) {
    const ExportPart& p = scene.parts[k];
    Eigen::Matrix4d to_scene = part_to_scene(scene, k);
    to_scene.topRows<3>() = turn * to_scene.topRows<3>();
    for (Eigen::Index v = 0; v < p.vertices.rows(); ++v) {
      const Eigen::Vector3d x = to_scene.topLeftCorner<3, 3>() * p.vertices.row(v).transpose() + to_scene.topRightCorner<3, 1>();
      for (int i = 0; i < 3; ++i) append_bytes(out, static_cast<float>(x(i)));
      append_bytes(out, static_cast<float>(p.uvs.rows() > 0 ? p.uvs(v, 0) : 0.0));
      append_bytes(out, static_cast<float>(p.uvs.rows() > 0 ? p.uvs(v, 1) : 0.0));
      append_bytes(out, static_cast<std::int32_t>(k));
    }
  }
  std::int64_t base = 0;
  for (const ExportPart& p : scene.parts) {
    for (Eigen::Index t = 0; t < p.triangles.rows(); ++t) {
      append_bytes(out, static_cast<std::uint8_t>(3));
      for (int i = 0; i < 3; ++i) append_bytes(out, static_cast<std::int32_t>(base + p.triangles(t, i)));
      append_bytes(out, static_cast<std::uint8_t>(p.triangle_material[static_cast<std::size_t>(t)]));
    }
    base += p.vertices.rows();
  }
  return out;
}

}  // namespace fissure::io_detail
