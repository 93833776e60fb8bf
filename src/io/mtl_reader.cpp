// Wavefront MTL, as far as a scene's look needs it: each `newmtl NAME`'s diffuse colour `Kd`
// and diffuse texture `map_Kd`; every other statement (Ka, Ks, Ns, d, illum, other maps, …) is
// read past. And the `mtllib` lines of an OBJ, which name the MTL files it uses.

#include "byte_cursor.hpp"
#include "surface_readers.hpp"

#include "fissure/base/error.hpp"

namespace fissure::io_detail {

std::vector<std::string> obj_material_libraries(std::string_view obj_bytes, const std::string& name) {
  ByteCursor c(obj_bytes, name);
  std::vector<std::string> libraries;
  while (!c.at_end()) {
    if (c.line_word() == "mtllib") {
      // One or more file names, separated by blanks (as the format has it).
      for (std::string_view w = c.line_word(); !w.empty() && w[0] != '#'; w = c.line_word()) libraries.emplace_back(w);
    }
    c.next_line();
  }
  return libraries;
}

std::vector<MtlMaterial> read_mtl(std::string_view bytes, const std::string& name) {
  ByteCursor c(bytes, name);
  std::vector<MtlMaterial> materials;
  while (!c.at_end()) {
    const std::string_view keyword = c.line_word();
    if (keyword == "newmtl") {
      const std::string_view material = c.line_word();
      if (material.empty()) c.fail("newmtl names no material");
      materials.push_back({std::string(material.substr(0, 200)), std::nullopt, {}});
    } else if (keyword == "Kd" || keyword == "map_Kd") {
      if (materials.empty()) c.fail(std::string(keyword) + " before any newmtl");
      MtlMaterial& m = materials.back();
      if (keyword == "Kd") {
        Eigen::Vector3d colour;
        for (int k = 0; k < 3; ++k) {
          const std::string_view w = c.line_word();
          double value = 0.0;
          if (w.empty() || !parse_double(w, value) || !(value >= 0.0 && value <= 1e3)) {
            c.fail("Kd of material " + m.name + " needs three non-negative numbers, got '" + std::string(w.substr(0, 40)) + "'");
          }
          colour(k) = value;
        }
        m.colour = colour.cwiseMin(1.0);  // a colour above 1 (some exporters' HDR) clamps to white
      } else {
        // Options (-bm 1, -s 1 1 1, …) come before the file name, which comes last.
        std::string_view last;
        for (std::string_view w = c.line_word(); !w.empty() && w[0] != '#'; w = c.line_word()) last = w;
        if (last.empty()) c.fail("map_Kd of material " + m.name + " names no file");
        m.texture = std::string(last);
      }
    }
    c.next_line();
  }
  return materials;
}

std::map<std::string, std::string> apply_material_libraries(const std::filesystem::path& obj, std::string_view obj_bytes,
                                                            SurfaceAppearance& look, std::vector<std::string>* warnings) {
  namespace fs = std::filesystem;
  std::map<std::string, std::string> textures;
  for (const std::string& library : obj_material_libraries(obj_bytes, obj.string())) {
    const fs::path file = obj.parent_path() / library;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) {
      if (warnings) {
        warnings->push_back(obj.string() + ": its material library " + library + " is not beside it (" + file.string() +
                            "); its materials keep the default colour");
      }
      continue;
    }
    const std::string name = obj.string() + ": its material library " + file.string();
    std::string bytes;
    try {
      bytes = read_input_bytes(file, name);
    } catch (const IoError& e) {
      throw IoError(obj.string() + ": its material library: " + e.what());
    }
    for (const MtlMaterial& m : read_mtl(bytes, name)) {
      for (SurfaceAppearance::Material& material : look.materials) {
        if (material.name != m.name) continue;
        if (m.colour) material.colour = *m.colour;
        if (!m.texture.empty()) textures[m.name] = m.texture;
      }
    }
  }
  return textures;
}

}  // namespace fissure::io_detail
