#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/io/surface_import.hpp"
#include "fissure/mesh/tile.hpp"

#include "test_support.hpp"

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include "test_shapes.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace fissure {
namespace {
namespace fs = std::filesystem;

std::string to_obj(const SurfaceMesh& s) {
  std::ostringstream out;
  out.precision(17);
  for (Eigen::Index v = 0; v < s.vertex_count(); ++v) out << "v " << s.vertices(v, 0) << ' ' << s.vertices(v, 1) << ' ' << s.vertices(v, 2) << '\n';
  for (Eigen::Index f = 0; f < s.face_count(); ++f) out << "f " << s.faces(f, 0) + 1 << ' ' << s.faces(f, 1) + 1 << ' ' << s.faces(f, 2) + 1 << '\n';
  return out.str();
}

std::string to_off(const SurfaceMesh& s) {
  std::ostringstream out;
  out.precision(17);
  out << "OFF\n" << s.vertex_count() << ' ' << s.face_count() << " 0\n";
  for (Eigen::Index v = 0; v < s.vertex_count(); ++v) out << s.vertices(v, 0) << ' ' << s.vertices(v, 1) << ' ' << s.vertices(v, 2) << '\n';
  for (Eigen::Index f = 0; f < s.face_count(); ++f) out << "3 " << s.faces(f, 0) << ' ' << s.faces(f, 1) << ' ' << s.faces(f, 2) << '\n';
  return out.str();
}

std::string to_ply(const SurfaceMesh& s) {
  std::ostringstream out;
  out.precision(17);
  out << "ply\nformat ascii 1.0\nelement vertex " << s.vertex_count()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << s.face_count()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index v = 0; v < s.vertex_count(); ++v) out << s.vertices(v, 0) << ' ' << s.vertices(v, 1) << ' ' << s.vertices(v, 2) << '\n';
  for (Eigen::Index f = 0; f < s.face_count(); ++f) out << "3 " << s.faces(f, 0) << ' ' << s.faces(f, 1) << ' ' << s.faces(f, 2) << '\n';
  return out.str();
}

// ASCII STL: one facet per triangle with its own three vertices (unwelded, as STL always is).
std::string to_stl(const SurfaceMesh& s) {
  std::ostringstream out;
  out.precision(17);
  out << "solid test\n";
  for (Eigen::Index f = 0; f < s.face_count(); ++f) {
    out << "facet normal 0 0 0\nouter loop\n";
    for (int k = 0; k < 3; ++k) {
      const auto v = s.vertices.row(s.faces(f, k));
      out << "vertex " << v(0) << ' ' << v(1) << ' ' << v(2) << '\n';
    }
    out << "endloop\nendfacet\n";
  }
  out << "endsolid test\n";
  return out.str();
}

TEST(SurfaceImport, PlainFormatsGiveTheSameSolid) {
  const fs::path dir = test::fresh_temp_dir("import-plain");
  const SurfaceMesh source = test::l_prism();
  ASSERT_NEAR(signed_volume(source), 1.5, 1e-15);
  const std::pair<const char*, std::string> files[] = {
      {"l.obj", to_obj(source)}, {"l.off", to_off(source)}, {"l.ply", to_ply(source)}, {"l.stl", to_stl(source)}};
  for (const auto& [file, text] : files) {
    write_file_atomically(dir / file, text);
    SurfaceRepairReport report;
    const SurfaceMesh s = import_surface(dir / file, report);
    // Coordinates are small integers and halves: exact in float32 too, so the volume is exact.
    EXPECT_NEAR(signed_volume(s), 1.5, 1e-12) << file;
    EXPECT_EQ(s.vertex_count(), 12) << file;
    EXPECT_EQ(s.face_count(), 20) << file;
  }
}

// glTF, GLB and FBX written by assimp's own exporters from the OBJ: the import must agree.
// FBX is exported as ASCII: assimp 5.2.5 cannot re-read its own binary FBX export ("FBX-Tokenize
// block offset is out of range"), a bug of that exporter, not of files from other tools.
TEST(SurfaceImport, ExportedGltfGlbFbxRoundTrip) {
  const fs::path dir = test::fresh_temp_dir("import-export");
  write_file_atomically(dir / "l.obj", to_obj(test::l_prism()));
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((dir / "l.obj").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  Assimp::Exporter exporter;
  for (const auto& [format, file] : {std::pair{"gltf2", "l.gltf"}, std::pair{"glb2", "l.glb"}, std::pair{"fbxa", "l.fbx"}}) {
    ASSERT_EQ(exporter.Export(scene, format, (dir / file).string()), AI_SUCCESS) << format << ": " << exporter.GetErrorString();
    SurfaceRepairReport report;
    const SurfaceMesh s = import_surface(dir / file, report);
    EXPECT_NEAR(signed_volume(s), 1.5, 1e-6) << file;  // float32 storage in glTF/FBX
  }
}

TEST(SurfaceImport, TileSpecOrFile) {
  SurfaceRepairReport report;
  EXPECT_NEAR(signed_volume(load_surface_input("tile:1,1,0.05", report)), 0.05, 1e-16);
  EXPECT_THROW(load_surface_input("tile:1,1", report), InvalidInput);
}

std::string import_error(const fs::path& path) {
  SurfaceRepairReport report;
  try {
    import_surface(path, report);
  } catch (const IoError& e) {
    return std::string("IoError: ") + e.what();
  } catch (const InvalidInput& e) {
    return std::string("InvalidInput: ") + e.what();
  }
  return "no error";
}

TEST(SurfaceImport, BadFilesAreNamed) {
  const fs::path dir = test::fresh_temp_dir("import-bad");
  auto expect = [&](const fs::path& path, const std::string& prefix) {
    const std::string e = import_error(path);
    EXPECT_EQ(e.rfind(prefix, 0), 0u) << e;
    EXPECT_NE(e.find(path.string()), std::string::npos) << e;
  };
  expect(dir / "missing.obj", "IoError");
  write_file_atomically(dir / "empty.stl", "");
  expect(dir / "empty.stl", "IoError");
  const std::string ply = to_ply(test::l_prism());
  write_file_atomically(dir / "cut.ply", ply.substr(0, ply.size() / 2));
  expect(dir / "cut.ply", "IoError");
  write_file_atomically(dir / "noise.glb", std::string(2000, '\x5a'));
  expect(dir / "noise.glb", "IoError");
  write_file_atomically(dir / "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
  expect(dir / "lines.obj", "");  // either error class, as long as it is named
  SurfaceMesh open = test::l_prism();
  open.faces.conservativeResize(19, 3);
  write_file_atomically(dir / "open.obj", to_obj(open));
  const std::string e = import_error(dir / "open.obj");
  EXPECT_NE(e.find("InvalidInput: " + (dir / "open.obj").string() + ": open"), std::string::npos) << e;
}

}  // namespace
}  // namespace fissure
