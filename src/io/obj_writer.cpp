// Wavefront OBJ and MTL: one object per part, its materials switched with usemtl inside it, so
// a part with crack and surface faces is one closed object in Blender, not two open groups.
#include "scene_encoders.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace fissure::io_detail {
namespace {

// OBJ and MTL statements are lines of words: a name (from an imported glTF, say) with blanks or
// control characters would end its statement early or start another. They become '_'.
std::string obj_name(const std::string& name) {
  std::string out = name.empty() ? std::string("unnamed") : name;
  for (char& c : out)
    if (static_cast<unsigned char>(c) <= ' ' || c == 0x7f) c = '_';
  return out;
}

// A part's object name: its path from the scene's root part, names joined by '/' (a '/' inside
// a name becomes '_'), so the fragments of two bodies, each named fragment_000, stay apart and
// Fissure's OBJ import rebuilds the hierarchy from it (scene_import.cpp).
std::string obj_object_name(const ExportScene& scene, std::size_t k) {
  std::string path;
  for (int at = static_cast<int>(k); at >= 0; at = scene.parts[static_cast<std::size_t>(at)].parent) {
    std::string name = obj_name(scene.parts[static_cast<std::size_t>(at)].name);
    std::replace(name.begin(), name.end(), '/', '_');
    path = path.empty() ? name : name + "/" + path;
  }
  return path;
}

}  // namespace

std::string encode_obj(const ExportScene& scene, const std::string& mtl_name, const Eigen::Matrix3d& turn) {
  const auto objects = std::count_if(scene.parts.begin(), scene.parts.end(), [](const ExportPart& p) { return p.triangles.rows() > 0; });
  std::string out = "# Fissure: " + std::to_string(objects) + (objects == 1 ? " object" : " objects") + ", metres\n";
  if (!mtl_name.empty()) out += "mtllib " + mtl_name + "\n";
  // OBJ indexes positions and UVs apart: each position is written once, so a part whose
  // vertices were split at UV seams reads back as one welded, closed surface with no merging.
  long long position_base = 0, uv_base = 0;  // OBJ indices are 1-based and global
  for (std::size_t k = 0; k < scene.parts.size(); ++k) {
    const ExportPart& part = scene.parts[k];
    if (part.triangles.rows() == 0) continue;  // a group: OBJ has no hierarchy
    Eigen::Matrix4d to_scene = part_to_scene(scene, k);
    to_scene.topRows<3>() = turn * to_scene.topRows<3>();
    out += "o " + obj_object_name(scene, k) + "\n";
    // Extras as comments, one line: OBJ has no place for them.
    out += "# extras " + nlohmann::json::parse(part.extras_json).dump() + "\n";
    std::map<std::array<double, 3>, long long> position_index;
    std::vector<long long> position_of(static_cast<std::size_t>(part.vertices.rows()));
    for (Eigen::Index v = 0; v < part.vertices.rows(); ++v) {
      const Eigen::Vector3d p = to_scene.topLeftCorner<3, 3>() * part.vertices.row(v).transpose() + to_scene.topRightCorner<3, 1>();
      const std::array<double, 3> x = {p(0), p(1), p(2)};
      const auto [it, inserted] = position_index.try_emplace(x, static_cast<long long>(position_index.size()));
      position_of[static_cast<std::size_t>(v)] = it->second;
      if (inserted) out += "v " + exact_number(x[0]) + " " + exact_number(x[1]) + " " + exact_number(x[2]) + "\n";
    }
    for (Eigen::Index v = 0; v < part.uvs.rows(); ++v)
      out += "vt " + exact_number(part.uvs(v, 0)) + " " + exact_number(part.uvs(v, 1)) + "\n";
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
      bool used = false;
      for (Eigen::Index t = 0; t < part.triangles.rows(); ++t) {
        if (part.triangle_material[static_cast<std::size_t>(t)] != static_cast<int>(m)) continue;
        if (!used) out += "usemtl " + obj_name(scene.materials[m].name) + "\n";
        used = true;
        out += "f";
        for (int i = 0; i < 3; ++i) {
          const int v = part.triangles(t, i);
          out += " " + std::to_string(position_base + position_of[static_cast<std::size_t>(v)] + 1);
          if (part.uvs.rows() > 0) out += "/" + std::to_string(uv_base + v + 1);
        }
        out += "\n";
      }
    }
    position_base += static_cast<long long>(position_index.size());
    uv_base += part.uvs.rows();
  }
  return out;
}

std::string encode_mtl(const ExportScene& scene) {
  std::string out = "# Fissure\n";
  for (const ExportMaterial& m : scene.materials) {
    out += "newmtl " + obj_name(m.name) + "\n";
    out += "Kd " + exact_number(m.colour.x()) + " " + exact_number(m.colour.y()) + " " + exact_number(m.colour.z()) + "\n";
    out += "Ka 0 0 0\nKs 0 0 0\nd 1\nillum 1\n";
    if (!m.texture.empty()) out += "map_Kd " + m.texture + "\n";
  }
  return out;
}

}  // namespace fissure::io_detail
