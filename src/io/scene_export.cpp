#include "fissure/io/scene_export.hpp"

#include "byte_cursor.hpp"
#include "scene_encoders.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>

namespace fissure {
namespace fs = std::filesystem;

namespace {

void check_scene(const ExportScene& scene) {
  const auto scene_extras = nlohmann::json::parse(scene.extras_json, nullptr, false);
  if (scene_extras.is_discarded() || !scene_extras.is_object()) throw InvalidInput("the scene's extras are not a JSON object");
  if (!scene.up.allFinite() || !(std::abs(scene.up.norm() - 1.0) <= 1e-9))
    throw InvalidInput("the scene's up axis is not a unit vector");
  const int materials = static_cast<int>(scene.materials.size());
  for (std::size_t p = 0; p < scene.parts.size(); ++p) {
    const ExportPart& part = scene.parts[p];
    const std::string who = "part " + std::to_string(p + 1) + " (" + part.name + ")";
    if (part.parent < -1 || part.parent >= static_cast<int>(p))
      throw InvalidInput(who + ": its parent " + std::to_string(part.parent + 1) + " is not an earlier part");
    if (part.uvs.rows() != 0 && part.uvs.rows() != part.vertices.rows())
      throw InvalidInput(who + ": " + std::to_string(part.uvs.rows()) + " UVs for " +
                         std::to_string(part.vertices.rows()) + " vertices");
    if (static_cast<Eigen::Index>(part.triangle_material.size()) != part.triangles.rows())
      throw InvalidInput(who + ": " + std::to_string(part.triangle_material.size()) + " triangle materials for " +
                         std::to_string(part.triangles.rows()) + " triangles");
    if (!part.vertices.allFinite() || !part.uvs.allFinite() || !part.translation.allFinite() || !part.linear.allFinite())
      throw InvalidInput(who + ": a position, UV or transform value is not finite");
    for (Eigen::Index t = 0; t < part.triangles.rows(); ++t) {
      for (int i = 0; i < 3; ++i)
        if (part.triangles(t, i) < 0 || part.triangles(t, i) >= part.vertices.rows())
          throw InvalidInput(who + ": triangle " + std::to_string(t + 1) + " indexes vertex " +
                             std::to_string(part.triangles(t, i) + 1) + " of " + std::to_string(part.vertices.rows()));
      const int m = part.triangle_material[static_cast<std::size_t>(t)];
      if (m < 0 || m >= materials)
        throw InvalidInput(who + ": triangle " + std::to_string(t + 1) + " has material " + std::to_string(m) +
                           " of " + std::to_string(materials));
    }
    const auto extras = nlohmann::json::parse(part.extras_json, nullptr, false);
    if (extras.is_discarded() || !extras.is_object()) throw InvalidInput(who + ": its extras are not a JSON object");
  }
}

}  // namespace

namespace io_detail {

std::string exact_number(double value) {
  char text[32];
  const auto [end, error] = std::to_chars(text, text + sizeof text, value);
  return error == std::errc() ? std::string(text, end) : std::string("0");
}

}  // namespace io_detail

Eigen::Matrix4d part_to_scene(const ExportScene& scene, std::size_t k) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (int p = static_cast<int>(k); p >= 0; p = scene.parts[static_cast<std::size_t>(p)].parent) {
    const ExportPart& part = scene.parts[static_cast<std::size_t>(p)];
    Eigen::Matrix4d local = Eigen::Matrix4d::Identity();
    local.topLeftCorner<3, 3>() = part.linear;
    local.topRightCorner<3, 1>() = part.translation;
    m = local * m;
  }
  return m;
}

std::optional<SceneFormat> scene_format_of(const fs::path& path) {
  const std::string ext = io_detail::lower_ascii(path.extension().string());
  if (ext == ".glb") return SceneFormat::Glb;
  if (ext == ".gltf") return SceneFormat::Gltf;
  if (ext == ".obj") return SceneFormat::Obj;
  if (ext == ".ply") return SceneFormat::Ply;
  return std::nullopt;
}

// The .mtl beside an OBJ: same name, extension .mtl.
static fs::path mtl_path_of(const fs::path& obj) { return fs::path(obj).replace_extension(".mtl"); }

void check_scene_output_path(const fs::path& path) {
  // Before the path's own checks: `-o x.stl` must not be written as something else under that name.
  if (!scene_format_of(path))
    throw IoError(path.string() + ": the output must end in " + std::string(kSceneFormats));
  for (const fs::path& file : scene_output_files(path)) check_output_path(file);
}

std::vector<fs::path> scene_output_files(const fs::path& path) {
  if (scene_format_of(path) == SceneFormat::Obj) return {path, mtl_path_of(path)};
  return {path};
}

Eigen::Matrix3d turn_between(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  if (from == to) return Eigen::Matrix3d::Identity();
  const double c = from.dot(to);
  if (c < -1.0 + 1e-12) {
    // Opposite: a half turn 2uuᵀ − I about u ⊥ from (from crossed with its least aligned axis).
    Eigen::Index least = 0;
    from.cwiseAbs().minCoeff(&least);
    const Eigen::Vector3d u = from.cross(Eigen::Vector3d::Unit(least)).normalized();
    return 2.0 * u * u.transpose() - Eigen::Matrix3d::Identity();
  }
  // Rodrigues with v = from × to, c = from · to: I + [v]× + [v]×² / (1 + c). Exact (entries 0 and
  // ±1) between coordinate axes, so a tile's +Z turned to glTF's +Y writes no round-off.
  const Eigen::Vector3d v = from.cross(to);
  Eigen::Matrix3d k;
  k << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return Eigen::Matrix3d::Identity() + k + k * k / (1.0 + c);
}

namespace {

// glTF's parts under a root node turning them from their frame to +Y up (see ExportScene::up).
ExportScene framed_for_gltf(const ExportScene& scene, const Eigen::Matrix3d& turn) {
  ExportScene out;
  out.materials = scene.materials;
  out.extras_json = scene.extras_json;
  out.parts.reserve(scene.parts.size() + 1);
  ExportPart root;
  root.name = scene.frame_name;
  root.linear = turn;
  const Eigen::Vector3d& u = scene.up;
  root.extras_json = "{\"up_of_children\":[" + io_detail::exact_number(u.x()) + "," + io_detail::exact_number(u.y()) + "," +
                     io_detail::exact_number(u.z()) + "]}";
  out.parts.push_back(std::move(root));
  for (const ExportPart& p : scene.parts) {
    out.parts.push_back(p);
    out.parts.back().parent = p.parent + 1;  // -1 (a root) becomes 0, the new root
  }
  return out;
}

}  // namespace

std::string encode_scene(const ExportScene& scene, SceneFormat format, const std::string& mtl_name) {
  check_scene(scene);
  const Eigen::Vector3d format_up = format == SceneFormat::Ply ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  const Eigen::Matrix3d turn = turn_between(scene.up, format_up);
  const bool turned = !turn.isIdentity(0.0);
  switch (format) {
    case SceneFormat::Glb: return io_detail::encode_gltf(turned ? framed_for_gltf(scene, turn) : scene, true);
    case SceneFormat::Gltf: return io_detail::encode_gltf(turned ? framed_for_gltf(scene, turn) : scene, false);
    case SceneFormat::Obj: return io_detail::encode_obj(scene, mtl_name, turn);
    case SceneFormat::Ply: return io_detail::encode_ply(scene, turn);
  }
  return {};
}

std::string encode_obj_materials(const ExportScene& scene) { return io_detail::encode_mtl(scene); }

void write_scene(const fs::path& path, const ExportScene& scene) {
  check_scene_output_path(path);
  const SceneFormat format = *scene_format_of(path);
  if (format == SceneFormat::Obj) {
    const fs::path mtl = mtl_path_of(path);
    const std::string obj = encode_scene(scene, format, mtl.filename().string());
    // The materials first: an .obj is never left naming a .mtl that was not written.
    write_file_atomically(mtl, encode_obj_materials(scene));
    write_file_atomically(path, obj);
    return;
  }
  write_file_atomically(path, encode_scene(scene, format));
}

}  // namespace fissure
