#pragma once
// The encoders behind write_scene() (include/fissure/io/scene_export.hpp), one file each; the
// scene has been checked (every index in range, every value finite) before they run.
#include "fissure/io/scene_export.hpp"

#include <bit>
#include <cstring>
#include <string>

namespace fissure::io_detail {

std::string encode_gltf(const ExportScene& scene, bool binary);
// `turn`: the rotation from the parts' frame to the format's (ExportScene::up).
std::string encode_obj(const ExportScene& scene, const std::string& mtl_name, const Eigen::Matrix3d& turn);
std::string encode_mtl(const ExportScene& scene);
std::string encode_ply(const ExportScene& scene, const Eigen::Matrix3d& turn);

static_assert(std::endian::native == std::endian::little, "binary glTF and PLY are written as the host's bytes");

// Appends `value`'s bytes, little-endian (the host's order, see above).
template <class T>
void append_bytes(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

// Shortest text that reads back to the same double (std::to_chars), for the text formats.
std::string exact_number(double value);

}  // namespace fissure::io_detail
