#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/io/msh.hpp"
#include "fissure/mesh/structured_box.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

namespace fissure {
namespace {
namespace fs = std::filesystem;

// A structured box with its six face sets, plus a 3-D set (the tets of the lower half) and a
// node set (the nodes on one edge), so every kind of physical group is exercised.
TetMesh box_with_sets() {
  const TetMesh box = make_structured_box({0, 0, 0}, {1.0, 0.7, 0.3}, 5, 4, 3);
  std::vector<NamedSet> sets = box.named_sets();
  NamedSet lower{"lower", 3, {}, {}, {}};
  for (int t = 0; t < box.tet_count(); ++t) {
    if (box.centroid(t).z() < 0.15) lower.tets.push_back(t);
  }
  for (int t : lower.tets)
    for (int a = 0; a < 4; ++a) lower.nodes.push_back(box.tets()(t, a));
  std::sort(lower.nodes.begin(), lower.nodes.end());
  lower.nodes.erase(std::unique(lower.nodes.begin(), lower.nodes.end()), lower.nodes.end());
  NamedSet edge{"edge", 1, {}, {}, {}};
  for (int v = 0; v < box.node_count(); ++v) {
    if (box.nodes()(v, 1) == 0.0 && box.nodes()(v, 2) == 0.0) edge.nodes.push_back(v);
  }
  sets.push_back(lower);
  sets.push_back(edge);
  return TetMesh(box.nodes(), box.tets(), "box", sets);
}

void expect_same_mesh(const TetMesh& a, const TetMesh& b, double tolerance) {
  ASSERT_EQ(a.node_count(), b.node_count());
  ASSERT_EQ(a.tet_count(), b.tet_count());
  EXPECT_LE((a.nodes() - b.nodes()).cwiseAbs().maxCoeff(), tolerance);
  EXPECT_EQ(a.tets(), b.tets());
  for (const NamedSet& set : a.named_sets()) {
    const NamedSet* other = b.find_named_set(set.name);
    ASSERT_NE(other, nullptr) << set.name;
    EXPECT_EQ(other->nodes, set.nodes) << set.name;
    EXPECT_EQ(other->tets, set.tets) << set.name;
    EXPECT_EQ(other->faces.size(), set.faces.size()) << set.name;
  }
}

TEST(Msh, BinaryRoundTripIsBitExact) {
  const fs::path dir = test::fresh_temp_dir("msh-bin");
  const TetMesh mesh = box_with_sets();
  write_msh(dir / "box.msh", mesh, {}, MshWriteOptions{true});
  const TetMesh back = read_msh(dir / "box.msh");
  expect_same_mesh(mesh, back, 0.0);
  EXPECT_EQ(back.source_name(), (dir / "box.msh").string());
}

TEST(Msh, AsciiRoundTripKeepsEverything) {
  const fs::path dir = test::fresh_temp_dir("msh-ascii");
  const TetMesh mesh = box_with_sets();
  write_msh(dir / "box.msh", mesh);
  // gmsh prints coordinates with 16 significant digits: 1 ulp-level differences are possible.
  expect_same_mesh(mesh, read_msh(dir / "box.msh"), 1e-15);
}

TEST(Msh, SameMeshSameBytes) {
  const fs::path dir = test::fresh_temp_dir("msh-det");
  const TetMesh mesh = box_with_sets();
  Eigen::MatrixXd u = Eigen::MatrixXd::Random(mesh.node_count(), 3);
  const std::vector<MshView> views{{"displacement", MshView::Kind::NodeData, u}};
  write_msh(dir / "a.msh", mesh, views);
  write_msh(dir / "b.msh", mesh, views);
  EXPECT_EQ(read_file(dir / "a.msh"), read_file(dir / "b.msh"));
}

bool have_gmsh() { return test::run_command("gmsh --version").exit_code == 0; }

// The real program: gmsh opens what Fissure writes, re-saves it in the other format, and Fissure
// reads that back; gmsh also parses the three views of a solve result.
TEST(Msh, GmshOpensWhatFissureWrites) {
  ASSERT_TRUE(have_gmsh()) << "the gmsh program is installed by scripts/install-deps.sh";
  const fs::path dir = test::fresh_temp_dir("msh-gmsh");
  const TetMesh mesh = box_with_sets();
  Eigen::MatrixXd stress(mesh.tet_count(), 9), smax(mesh.tet_count(), 1), u(mesh.node_count(), 3);
  stress.setRandom();
  smax.setRandom();
  u.setRandom();
  for (bool binary : {false, true}) {
    const fs::path result = dir / (binary ? "result-bin.msh" : "result.msh");
    write_msh(result,
              mesh,
              {{"displacement", MshView::Kind::NodeData, u},
               {"stress", MshView::Kind::ElementData, stress},
               {"max_principal_stress", MshView::Kind::ElementData, smax}},
              MshWriteOptions{binary});
    // -save_all: gmsh otherwise saves only elements in physical groups (its documented default).
    // MSH 2.2 then writes every element without its group; MSH 4.1 keeps groups on entities.
    for (const char* format : {"msh22", "msh41"}) {
      const fs::path resaved = dir / (std::string("resaved-") + format + ".msh");
      const auto save = test::run_command("gmsh " + result.string() + " -0 -save_all -format " + format + " -o " +
                                          resaved.string());
      ASSERT_EQ(save.exit_code, 0) << save.output;
      EXPECT_EQ(save.output.find("Error"), std::string::npos) << save.output;
      const TetMesh back = read_msh(resaved);
      EXPECT_EQ(back.tet_count(), mesh.tet_count());
      EXPECT_EQ(back.node_count(), mesh.node_count());
      EXPECT_NEAR(back.total_volume(), mesh.total_volume(), 1e-12);
      if (std::string(format) == "msh41") {
        expect_same_mesh(mesh, back, 1e-15);
      }
    }

    const fs::path script = dir / "count.geo";
    write_file_atomically(script, "Merge \"" + result.string() +
                                      "\";\nPrintf(\"views=%g steps=%g\", PostProcessing.NbViews, "
                                      "View[2].NbTimeStep);\n");
    const auto count = test::run_command("gmsh " + script.string() + " -0 -o " + (dir / "x.geo_unrolled").string());
    EXPECT_EQ(count.exit_code, 0) << count.output;
    EXPECT_NE(count.output.find("views=3 steps=1"), std::string::npos) << count.output;
  }
}

std::string write_geo(const fs::path& dir) {
  const fs::path geo = dir / "box.geo";
  write_file_atomically(geo,
                        "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 0.5, 0.2};\n"
                        "Physical Volume(\"solid\") = {1};\nPhysical Surface(\"bottom\") = {5};\n"
                        "Mesh.CharacteristicLengthMax = 0.15;\n");
  return geo.string();
}

TEST(Msh, ReadsWhatGmshWrites) {
  ASSERT_TRUE(have_gmsh());
  const fs::path dir = test::fresh_temp_dir("msh-read");
  const std::string geo = write_geo(dir);
  for (const char* format : {"msh22", "msh41"}) {
    for (bool binary : {false, true}) {
      const fs::path out = dir / (std::string(format) + (binary ? "-bin" : "") + ".msh");
      const auto run = test::run_command("gmsh " + geo + " -3 -format " + format + (binary ? " -bin" : "") +
                                         " -o " + out.string());
      ASSERT_EQ(run.exit_code, 0) << run.output;
      const TetMesh mesh = read_msh(out);
      SCOPED_TRACE(out.string());
      EXPECT_GT(mesh.tet_count(), 100);
      // The box is meshed exactly (planar faces), so the tets fill it to round-off.
      EXPECT_NEAR(mesh.total_volume(), 0.1, 1e-12);
      const NamedSet* bottom = mesh.find_named_set("bottom");
      ASSERT_NE(bottom, nullptr);
      EXPECT_EQ(bottom->dimension, 2);
      EXPECT_FALSE(bottom->faces.empty());
      for (int v : bottom->nodes) EXPECT_NEAR(mesh.nodes()(v, 2), 0.0, 1e-12);
      const NamedSet* solid = mesh.find_named_set("solid");
      ASSERT_NE(solid, nullptr);
      EXPECT_EQ(static_cast<int>(solid->tets.size()), mesh.tet_count());
    }
  }
}

std::string read_error(const fs::path& path) {
  try {
    read_msh(path);
  } catch (const IoError& e) {
    return std::string("IoError: ") + e.what();
  } catch (const InvalidInput& e) {
    return std::string("InvalidInput: ") + e.what();
  }
  return "no error";
}

TEST(Msh, BadFilesAreRefusedWithTheFileNamed) {
  const fs::path dir = test::fresh_temp_dir("msh-bad");
  const TetMesh mesh = box_with_sets();
  write_msh(dir / "good.msh", mesh);
  const std::string good = read_file(dir / "good.msh");

  auto expect = [&](const fs::path& path, const std::string& kind, const std::string& words) {
    const std::string e = read_error(path);
    EXPECT_EQ(e.rfind(kind, 0), 0u) << e;
    EXPECT_NE(e.find(path.string()), std::string::npos) << e;
    EXPECT_NE(e.find(words), std::string::npos) << e;
  };
  expect(dir / "missing.msh", "IoError", "no such file");
  write_file_atomically(dir / "empty.msh", "");
  expect(dir / "empty.msh", "IoError", "empty");
  write_file_atomically(dir / "half.msh", good.substr(0, good.size() / 2));
  expect(dir / "half.msh", "IoError", "truncated");
  // A PNG signature and some bytes, renamed .msh.
  write_file_atomically(dir / "picture.msh", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16) + std::string(100, '\x07'));
  expect(dir / "picture.msh", "IoError", "not a gmsh MSH file");
  write_file_atomically(dir / "v3.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n");
  expect(dir / "v3.msh", "IoError", "unsupported MSH version");
  // Elements section damaged: a tet that names a node that does not exist.
  std::string broken = good;
  const std::size_t at = broken.find("$Elements");
  broken.replace(broken.find('\n', broken.find("\n4 ", at) + 1) - 1, 1, "9999999");
  write_file_atomically(dir / "broken.msh", broken);
  const std::string broken_error = read_error(dir / "broken.msh");
  EXPECT_EQ(broken_error.rfind("IoError", 0), 0u) << broken_error;

  // Only triangles: a 2-D mesh.
  if (have_gmsh()) {
    write_file_atomically(dir / "square.geo", "SetFactory(\"OpenCASCADE\");\nRectangle(1) = {0, 0, 0, 1, 1};\n");
    const auto run = test::run_command("gmsh " + (dir / "square.geo").string() + " -2 -o " + (dir / "square.msh").string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    expect(dir / "square.msh", "InvalidInput", "holds no tetrahedra");
  }

  // An inverted tet: swap two nodes of tet 3 in a written file; the error names file and tet.
  Eigen::MatrixX4i tets = mesh.tets();
  std::swap(tets(3, 0), tets(3, 1));
  // Build the file through gmsh directly would refuse nothing, so write a hand-made MSH 2.2.
  std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + std::to_string(mesh.node_count()) + "\n";
  for (int v = 0; v < mesh.node_count(); ++v) {
    char line[128];
    std::snprintf(line, sizeof line, "%d %.17g %.17g %.17g\n", v + 1, mesh.nodes()(v, 0), mesh.nodes()(v, 1), mesh.nodes()(v, 2));
    text += line;
  }
  text += "$EndNodes\n$Elements\n" + std::to_string(mesh.tet_count()) + "\n";
  for (int t = 0; t < mesh.tet_count(); ++t) {
    text += std::to_string(t + 1) + " 4 2 0 1";
    for (int a = 0; a < 4; ++a) text += " " + std::to_string(tets(t, a) + 1);
    text += "\n";
  }
  text += "$EndElements\n";
  write_file_atomically(dir / "inverted.msh", text);
  // Named by its element tag in the file (t + 1 = 4), as gmsh shows it.
  expect(dir / "inverted.msh", "InvalidInput", "tet 4 is inverted");

  // A directory named like a mesh.
  fs::create_directories(dir / "folder.msh");
  expect(dir / "folder.msh", "IoError", "is a directory");
}

// Random corruption (byte flips, deletions, insertions, cuts) of valid files in all four
// formats: the reader must refuse cleanly or read a mesh, never crash or hang. gmsh 4.8.4's own
// reader segfaults on ~2 % of such files, which is why Fissure parses MSH itself.
TEST(Msh, CorruptFilesNeverCrashTheReader) {
  const fs::path dir = test::fresh_temp_dir("msh-fuzz");
  const TetMesh mesh = box_with_sets();
  std::vector<std::string> originals;
  write_msh(dir / "a41.msh", mesh);
  write_msh(dir / "b41.msh", mesh, {{"u", MshView::Kind::NodeData, Eigen::MatrixXd::Random(mesh.node_count(), 3)}},
            MshWriteOptions{true});
  originals.push_back(read_file(dir / "a41.msh"));
  originals.push_back(read_file(dir / "b41.msh"));
  if (have_gmsh()) {
    for (const char* format : {"msh22", "msh22 -bin"}) {
      const fs::path out = dir / (std::string("g") + (format[5] ? "b" : "a") + "22.msh");
      ASSERT_EQ(test::run_command("gmsh " + (dir / "a41.msh").string() + " -0 -save_all -format " + format + " -o " + out.string()).exit_code, 0);
      originals.push_back(read_file(out));
    }
  }
  Rng rng(2026);
  int refused = 0, read = 0;
  for (std::size_t f = 0; f < originals.size(); ++f) {
    for (int trial = 0; trial < 500; ++trial) {
      std::string bytes = originals[f];
      const int edits = 1 + static_cast<int>(rng.uniform_index(4));
      for (int e = 0; e < edits && !bytes.empty(); ++e) {
        const std::size_t at = rng.uniform_index(bytes.size());
        switch (rng.uniform_index(4)) {
          case 0: bytes[at] = static_cast<char>(rng.uniform_index(256)); break;
          case 1: bytes.erase(at, 1 + rng.uniform_index(16)); break;
          case 2: bytes.insert(at, std::string(1 + rng.uniform_index(8), static_cast<char>(rng.uniform_index(256)))); break;
          default: bytes.resize(at); break;
        }
      }
      const fs::path path = dir / "fuzz.msh";
      write_file_atomically(path, bytes);
      try {
        const TetMesh m = read_msh(path);
        EXPECT_GT(m.tet_count(), 0);
        ++read;
      } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
        ++refused;
      } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
        ++refused;
      }
    }
  }
  std::printf("corrupted files: %d refused with a message, %d still read as meshes\n", refused, read);
  EXPECT_GT(refused, 0);
}

TEST(Msh, ViewsAreValidated) {
  const fs::path dir = test::fresh_temp_dir("msh-views");
  const TetMesh mesh = box_with_sets();
  auto error = [&](const MshView& view) {
    try {
      write_msh(dir / "v.msh", mesh, {view});
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error({"u", MshView::Kind::NodeData, Eigen::MatrixXd::Zero(3, 3)}).find("view 'u' has 3 rows"), std::string::npos);
  EXPECT_NE(error({"s", MshView::Kind::ElementData, Eigen::MatrixXd::Zero(mesh.tet_count(), 6)}).find("6 components"),
            std::string::npos);
  Eigen::MatrixXd nan = Eigen::MatrixXd::Zero(mesh.node_count(), 1);
  nan(4, 0) = std::nan("");
  EXPECT_NE(error({"p", MshView::Kind::NodeData, nan}).find("non-finite"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "v.msh"));
  EXPECT_THROW(write_msh(dir / "no-such-dir" / "x.msh", mesh), IoError);
}

}  // namespace
}  // namespace fissure
