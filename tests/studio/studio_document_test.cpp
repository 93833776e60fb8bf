#include "body_geometry.hpp"
#include "studio_commands.hpp"
#include "studio_document.hpp"
#include "studio_jobs.hpp"

#include "test_support.hpp"

#include "fissure/base/error.hpp"
#include "fissure/io/scene_export.hpp"
#include "fissure/io/scene_import.hpp"
#include "fissure/mesh/surface_mesh.hpp"
#include "fissure/scene/fragment_export.hpp"
#include "fissure/scene/scene_body_check.hpp"

#include <QCoreApplication>
#include <QElapsedTimer>

#include <gtest/gtest.h>

#include <fstream>
#include <numeric>

namespace fissure::studio {
namespace {

namespace fs = std::filesystem;

const fs::path kStreet = test::source_dir() / "assets/scenes/street.glb";

// Runs the event loop until the jobs are idle (a fracture of one 6000-tet slab takes about a
// second; 120 s is for a slow sanitizer build).
void wait_for(const StudioJobs& jobs) {
  QElapsedTimer t;
  t.start();
  while ((jobs.fracture_running() || jobs.age_running()) && t.elapsed() < 120000) QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
  QCoreApplication::processEvents();
  ASSERT_FALSE(jobs.fracture_running() || jobs.age_running()) << "the jobs did not finish in 120 s";
}

int body_named(const StudioDocument& d, const std::string& path) {
  for (int b = 0; b < static_cast<int>(d.bodies().size()); ++b)
    if (d.bodies()[static_cast<std::size_t>(b)].path == path) return b;
  return -1;
}

double total_volume(const std::vector<FragmentMesh>& fragments) {
  return std::accumulate(fragments.begin(), fragments.end(), 0.0, [](double s, const FragmentMesh& m) { return s + m.volume; });
}

// A file that does not open leaves what was open as it was: the scene, its assignments, its undo history.
TEST(StudioDocument, AFailedOpenChangesNothing) {
  StudioDocument d;
  d.open(QString::fromStdString(kStreet.string()));
  d.undo_stack()->push(new AssignMaterialCommand(&d, AssignMaterialCommand::Target::SceneMaterial, "concrete", "concrete"));
  const std::size_t bodies = d.bodies().size();
  const fs::path dir = test::fresh_temp_dir("studio-bad-open");
  std::ofstream(dir / "broken.glb") << "glTF but not really";
  // A project whose scene is there but whose support does not parse.
  fs::copy_file(kStreet, dir / "street.glb");
  std::ofstream(dir / "project.json") << R"({"fissure_project": 1, "scene": "street.glb", "seed": 1, "assign": {},
    "bodies": {"/street/curb": {"supports": ["box:1,2,3"]}}})";
  for (const fs::path& bad : {dir / "missing.glb", dir / "broken.glb", dir / "project.json"}) {
    EXPECT_THROW(d.open(QString::fromStdString(bad.string())), Error) << bad;
    EXPECT_EQ(d.bodies().size(), bodies);
    EXPECT_EQ(d.material_of(0), "concrete");
    EXPECT_EQ(d.undo_stack()->count(), 1);
    EXPECT_EQ(d.path().toStdString(), kStreet.string());
  }
}

// Assignments: a scene material's reaches every body using it, a node's overrides it for that
// node; undo and redo walk back and forth through them.
TEST(StudioDocument, AssignmentsAreUndoable) {
  StudioDocument d;
  d.open(QString::fromStdString(kStreet.string()));
  const int slab = body_named(d, "/street/sidewalk/slab_01"), curb = body_named(d, "/street/curb");
  ASSERT_GE(slab, 0);
  ASSERT_GE(curb, 0);
  EXPECT_EQ(d.material_of(slab), "");
  d.undo_stack()->push(new AssignMaterialCommand(&d, AssignMaterialCommand::Target::SceneMaterial, "concrete", "concrete"));
  const auto concrete = d.bodies_with_material("concrete");
  EXPECT_GE(concrete.size(), 20u);  // the ≥ 20 slabs at least
  d.undo_stack()->push(new AssignMaterialCommand(&d, AssignMaterialCommand::Target::Node, "/street/sidewalk/slab_01", "plaster"));
  EXPECT_EQ(d.material_of(slab), "plaster");
  EXPECT_EQ(d.bodies_with_material("concrete").size(), concrete.size() - 1);
  d.undo_stack()->undo();
  EXPECT_EQ(d.material_of(slab), "concrete");
  d.undo_stack()->undo();
  EXPECT_EQ(d.material_of(slab), "");
  EXPECT_TRUE(d.bodies_with_material("concrete").empty());
  d.undo_stack()->redo();
  d.undo_stack()->redo();
  EXPECT_EQ(d.material_of(slab), "plaster");
}

// Fracturing a body in the studio gives what `fissure scene fracture` gives it (the same
// seed and fragments), its fragments fill the body, and undo/redo swap the result without a
// new simulation. The age slider's fragments at an earlier age come from the same cracks.
TEST(StudioDocument, FractureAgeAndUndo) {
  StudioDocument d;
  d.open(QString::fromStdString(kStreet.string()));
  d.set_simulation_age(50.0);  // the street demo's age: concrete's own leaves many slabs whole
  StudioJobs jobs(&d);
  jobs.set_cache_directory(test::binary_dir() / "test-cache");
  const int slab = body_named(d, "/street/sidewalk/slab_03");
  d.undo_stack()->push(new AssignMaterialCommand(&d, AssignMaterialCommand::Target::SceneMaterial, "concrete", "concrete"));
  QString finished;
  QObject::connect(&jobs, &StudioJobs::fracture_finished, [&](const QString& s) { finished = s; });
  ASSERT_TRUE(jobs.fracture({slab}, "Fracture"));
  EXPECT_FALSE(jobs.fracture({slab}, "again")) << "a second fracture while one runs is refused";
  wait_for(jobs);
  EXPECT_EQ(finished, "1 body fractured");
  const auto state = d.fracture_of(slab);
  ASSERT_TRUE(state);
  EXPECT_EQ(d.undo_stack()->count(), 2);

  // The scene module's own run of this body, as `fissure scene fracture --assign
  // /street/sidewalk/slab_03=concrete` makes it (scene_fracture.hpp: a body's result depends on
  // its path, the project seed and its material, not on the other bodies).
  SceneFractureOptions cli;
  cli.assignments.by_path["/street/sidewalk/slab_03"] = "concrete";
  cli.cache_dir = test::binary_dir() / "test-cache";
  cli.age = 50.0;
  const SceneFracture whole = fracture_scene(import_scene(kStreet), cli);
  ASSERT_TRUE(whole.results[static_cast<std::size_t>(slab)]);
  // The CLI keeps no tet meshes (thousands of bodies hold only their fragments); the studio does.
  EXPECT_FALSE(whole.results[static_cast<std::size_t>(slab)]->fracture.mesh);
  EXPECT_TRUE(state->fractured.fracture.mesh);
  EXPECT_EQ(state->report.seed, body_seed(1, "/street/sidewalk/slab_03"));
  const auto shown = d.shown_fragments(slab);
  ASSERT_TRUE(shown);
  const auto& cli_fragments = whole.results[static_cast<std::size_t>(slab)]->fracture.fragments;
  ASSERT_EQ(shown->size(), cli_fragments.size());
  for (std::size_t f = 0; f < shown->size(); ++f) EXPECT_EQ((*shown)[f].volume, cli_fragments[f].volume) << f;
  ASSERT_GT(shown->size(), 1u) << "concrete at its own age breaks a slab";
  // The fragments fill the slab (0.6 × 0.05 × 0.6 m in float32, as the GLB stores it): the exact
  // construction conserves volume to round-off; 1e-9 relative is far above it and far below a
  // lost tet (~1e-4).
  const double volume = signed_volume(check_scene_body(d.scene(), d.bodies()[static_cast<std::size_t>(slab)]).world);
  EXPECT_NEAR(volume, 0.018, 1e-6);
  EXPECT_NEAR(total_volume(*shown), volume, 1e-9 * volume);

  // What the viewport draws of it: a range per fragment, every triangle, crack lines.
  const BodyGeometry g = fragment_geometry(*shown, Eigen::Vector3d::Constant(0.5), Eigen::Vector3d::Zero());
  EXPECT_EQ(g.ranges.size(), shown->size());
  int triangles = 0;
  for (const FragmentMesh& m : *shown) triangles += static_cast<int>(m.triangles.rows());
  EXPECT_EQ(g.triangle_count(), triangles);
  EXPECT_GT(g.lines.size(), 0u);

  // Halfway through its age, fewer cracks and no more fragments; from the same cracks.
  const double age = state->fractured.fracture.result.simulated_age;
  d.set_age(0.5 * age);
  const int half = d.shown_cracks(slab);
  EXPECT_LT(half, state->crack_count());
  wait_for(jobs);
  int cracks = -1;
  const auto earlier = d.shown_fragments(slab, &cracks);
  EXPECT_EQ(cracks, half);
  EXPECT_LE(earlier->size(), shown->size());
  EXPECT_NEAR(total_volume(*earlier), volume, 1e-9 * volume);
  d.set_age(std::nullopt);
  EXPECT_EQ(d.shown_fragments(slab), shown) << "back at full age: the fragments first meshed, not new ones";

  // Undo: the slab is whole again; redo: the very same result, no new simulation.
  d.undo_stack()->undo();
  EXPECT_FALSE(d.fracture_of(slab));
  d.undo_stack()->redo();
  EXPECT_EQ(d.fracture_of(slab), state);
}

// Moving, hiding and deleting fragments are undoable; the export writes what is shown: a moved
// fragment where it was moved, a deleted one not at all, every other node as it was.
TEST(StudioDocument, FragmentEditsAndExport) {
  StudioDocument d;
  d.open(QString::fromStdString(kStreet.string()));
  d.set_simulation_age(50.0);  // the street demo's age: concrete's own leaves many slabs whole
  StudioJobs jobs(&d);
  jobs.set_cache_directory(test::binary_dir() / "test-cache");
  const int slab = body_named(d, "/street/sidewalk/slab_03");
  d.undo_stack()->push(new AssignMaterialCommand(&d, AssignMaterialCommand::Target::Node, "/street/sidewalk/slab_03", "concrete"));
  ASSERT_TRUE(jobs.fracture({slab}, "Fracture"));
  wait_for(jobs);
  int cracks = 0;
  const auto fragments = d.shown_fragments(slab, &cracks);
  ASSERT_TRUE(fragments);
  ASSERT_GE(fragments->size(), 3u);
  const int n = static_cast<int>(fragments->size());
  FragmentEdit moved;
  moved.offset = Eigen::Vector3d(0, 0.5, 0);
  FragmentEdit deleted;
  deleted.deleted = true;
  d.undo_stack()->push(new FragmentEditCommand(&d, {{{slab, cracks, 0}, moved}, {{slab, cracks, 1}, deleted}}, "edit"));
  EXPECT_EQ(d.edit_of({slab, cracks, 0}), moved);
  d.undo_stack()->undo();
  EXPECT_EQ(d.edit_of({slab, cracks, 0}), FragmentEdit());
  EXPECT_EQ(d.edit_of({slab, cracks, 1}), FragmentEdit());
  d.undo_stack()->redo();

  const fs::path dir = test::fresh_temp_dir("studio-export");
  write_scene(dir / "out.glb", d.export_scene());
  const ImportedScene back = import_scene(dir / "out.glb");
  const ImportedScene original = import_scene(kStreet);
  // The slab node gains n − 1 fragment children (one deleted); every other node is kept.
  EXPECT_EQ(back.nodes.size(), original.nodes.size() + static_cast<std::size_t>(n - 1));
  for (const SceneNode& node : original.nodes) {
    const bool found = std::any_of(back.nodes.begin(), back.nodes.end(), [&](const SceneNode& m) { return m.path == node.path; });
    EXPECT_TRUE(found) << node.path;
  }
  // The moved fragment (still the first, fragment_000: the deleted one was the second) lies 0.5 m
  // above where it broke; the next one exported (the slab's third) where it broke. Float32 files: 1e-5 m.
  auto lowest_of = [&](const std::string& path) {
    double lowest = 1e9;
    for (const SceneBody& body : scene_bodies(back)) {
      if (body.path != path) continue;
      for (int m : body.meshes) {
        const SceneMesh& mesh = back.meshes[static_cast<std::size_t>(m)];
        for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
          lowest = std::min(lowest, (body.world * mesh.vertices.row(v).transpose().homogeneous())(1));
      }
    }
    return lowest;
  };
  const std::string first = "/street/sidewalk/slab_03/" + fragment_name(0, n - 1);
  const std::string second = "/street/sidewalk/slab_03/" + fragment_name(1, n - 1);
  EXPECT_NEAR(lowest_of(first), (*fragments)[0].vertices.col(1).minCoeff() + 0.5, 1e-5);
  EXPECT_NEAR(lowest_of(second), (*fragments)[2].vertices.col(1).minCoeff(), 1e-5);

  // Only the selected fragments: their own file, n parts at most, no street.
  const std::set<FragmentRef> chosen{{slab, cracks, 0}, {slab, cracks, 2}};
  write_scene(dir / "two.glb", d.export_scene(&chosen));
  const ImportedScene two = import_scene(dir / "two.glb");
  EXPECT_EQ(scene_bodies(two).size(), 2u);
  double highest = -1e9;
  for (const SceneBody& body : scene_bodies(two))
    for (int m : body.meshes) {
      const SceneMesh& mesh = two.meshes[static_cast<std::size_t>(m)];
      for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
        highest = std::max(highest, (body.world * mesh.vertices.row(v).transpose().homogeneous())(1));
    }
  EXPECT_NEAR(highest, (*fragments)[0].vertices.col(1).maxCoeff() + 0.5, 1e-5) << "fragment 0 exported where it was moved";
}

// A project saved by the studio opens in the studio and in the CLI with the same assignments.
TEST(StudioDocument, ProjectsRoundTrip) {
  const fs::path dir = test::fresh_temp_dir("studio-project");
  StudioDocument d;
  d.open(QString::fromStdString(kStreet.string()));
  d.undo_stack()->push(new AssignMaterialCommand(&d, AssignMaterialCommand::Target::SceneMaterial, "concrete", "concrete"));
  d.save_project(QString::fromStdString((dir / "p.json").string()));
  const SceneProject p = read_scene_project(dir / "p.json");
  EXPECT_EQ(p.assignments.by_material.at("concrete"), "concrete");
  EXPECT_TRUE(fs::equivalent(project_path(dir / "p.json", p.scene), kStreet));
  StudioDocument e;
  e.open(QString::fromStdString((dir / "p.json").string()));
  EXPECT_EQ(e.material_of(0), "concrete");
  EXPECT_EQ(e.bodies().size(), d.bodies().size());
}

}  // namespace
}  // namespace fissure::studio
