// Fissure Studio driven as a new user would, under xvfb-run (Mesa llvmpipe, OpenGL 3.3 core):
// open the demo street, click a slab, assign concrete from the library, fracture, scrub the age,
// undo and redo, move a fragment, export, and re-import the export. Screenshots go to
// build/studio-screenshots/ (look at them).
#include "main_window.hpp"

#include "test_support.hpp"

#include "fissure/io/scene_import.hpp"
#include "fissure/scene/scene_body_check.hpp"

#include <QApplication>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QListWidget>
#include <QPushButton>
#include <QSlider>
#include <QTest>
#include <QTreeView>

#include <gtest/gtest.h>

#include <filesystem>

namespace fissure::studio {
namespace {

namespace fs = std::filesystem;

fs::path screenshots() {
  const fs::path dir = test::binary_dir() / "studio-screenshots";
  fs::create_directories(dir);
  return dir;
}

void save_screenshot(MainWindow& w, const std::string& name) {
  QApplication::processEvents();
  const QImage image = w.grab().toImage();
  ASSERT_FALSE(image.isNull());
  ASSERT_TRUE(image.save(QString::fromStdString((screenshots() / name).string())));
}

// Runs the event loop until `done` or 120 s; returns the longest gap between two runs of the
// loop meanwhile (ms): how long the UI stalled.
template <typename Done>
qint64 run_until(Done done) {
  QElapsedTimer t, gap;
  t.start();
  gap.start();
  qint64 longest = 0;
  while (!done() && t.elapsed() < 120000) {
    QApplication::processEvents(QEventLoop::AllEvents, 5);
    longest = std::max(longest, gap.restart());
  }
  QApplication::processEvents();
  return longest;
}

// A pixel of the viewport showing body `path` (its middle, of the pixels that pick it).
QPoint pixel_of(Viewport* v, const std::string& path, const StudioDocument& d) {
  long sx = 0, sy = 0, n = 0;
  for (int y = 0; y < v->height(); y += 6)
    for (int x = 0; x < v->width(); x += 6) {
      const FragmentRef r = v->pick(x, y);
      if (r.body >= 0 && d.bodies()[static_cast<std::size_t>(r.body)].path == path) {
        sx += x;
        sy += y;
        ++n;
      }
    }
  return n ? QPoint(static_cast<int>(sx / n), static_cast<int>(sy / n)) : QPoint(-1, -1);
}

QPushButton* button(MainWindow& w, const QString& text) {
  for (QPushButton* b : w.findChildren<QPushButton*>())
    if (b->text() == text) return b;
  return nullptr;
}

TEST(StudioGui, ANewUsersSession) {
  MainWindow w;
  QStringList errors;
  w.report_error = [&](const QString& m) { errors << m; };
  w.jobs()->set_cache_directory(test::binary_dir() / "test-cache");
  w.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&w));
  // Shortcuts reach the active window only (xvfb has no window manager to activate it).
  w.activateWindow();
  ASSERT_TRUE(QTest::qWaitForWindowActive(&w));

  // A scene that is not there: one message naming it, nothing opened.
  EXPECT_FALSE(w.open_file("/nonexistent/street.glb"));
  ASSERT_EQ(errors.size(), 1);
  EXPECT_TRUE(errors[0].contains("/nonexistent/street.glb")) << errors[0].toStdString();
  EXPECT_FALSE(w.document()->is_open());

  // Nothing open: export and save say so instead of writing an empty scene.
  EXPECT_FALSE(w.export_to(QString::fromStdString((test::fresh_temp_dir("studio-gui-empty") / "x.glb").string()), false));
  EXPECT_FALSE(w.save_project_to(QString::fromStdString((test::fresh_temp_dir("studio-gui-empty") / "p.json").string())));
  ASSERT_EQ(errors.size(), 3);
  EXPECT_TRUE(errors.back().contains("open a scene first")) << errors.back().toStdString();
  errors.clear();
  errors << "(the missing scene)";

  const fs::path street = test::source_dir() / "assets/scenes/street.glb";
  ASSERT_TRUE(w.open_file(QString::fromStdString(street.string())));
  QApplication::processEvents();
  ASSERT_TRUE(w.viewport()->gl_ready()) << w.viewport()->gl_error().toStdString();
  save_screenshot(w, "01-street-opened.png");

  // Click the slab in the view: it is selected, in the outliner too.
  const std::string slab_path = "/street/sidewalk/slab_05";
  const QPoint p = pixel_of(w.viewport(), slab_path, *w.document());
  ASSERT_GE(p.x(), 0) << "slab_05 is not in view after opening";
  QTest::mouseClick(w.viewport(), Qt::LeftButton, {}, p);
  ASSERT_EQ(w.selection()->bodies().size(), 1u);
  const int slab = w.selection()->bodies().front();
  EXPECT_EQ(w.document()->bodies()[static_cast<std::size_t>(slab)].path, slab_path);
  EXPECT_EQ(w.outliner()->selectionModel()->selectedRows().size(), 1);

  // Fracturing with no material says what to do and changes nothing.
  QTest::keyClick(&w, Qt::Key_F);
  EXPECT_EQ(errors.size(), 2);
  EXPECT_TRUE(errors.back().contains("No fracture material")) << errors.back().toStdString();

  // The library's concrete, assigned to the slab's scene material.
  const auto found = w.library()->findItems("concrete", Qt::MatchExactly);
  ASSERT_EQ(found.size(), 1);
  w.library()->setCurrentItem(found.front());
  QTest::mouseClick(button(w, "Assign to their scene material"), Qt::LeftButton);
  EXPECT_EQ(w.document()->material_of(slab), "concrete");
  EXPECT_GE(w.document()->bodies_with_material("concrete").size(), 20u);

  // The street is aged 50 (as the demo does): concrete's own age leaves many slabs whole.
  w.simulation_age()->setValue(50.0);
  EXPECT_EQ(w.document()->simulation_age(), std::optional<double>(50.0));
  // F fractures the selection in the background; the UI keeps running meanwhile.
  QTest::keyClick(&w, Qt::Key_F);
  ASSERT_TRUE(w.jobs()->fracture_running());
  QElapsedTimer fracture_time;
  fracture_time.start();
  const qint64 stall = run_until([&] { return !w.jobs()->fracture_running(); });
  const qint64 took = fracture_time.elapsed();
  ASSERT_TRUE(w.document()->fracture_of(slab)) << errors.join("\n").toStdString();
  std::cout << "longest UI stall while a slab fractured: " << stall << " ms of " << took << " ms\n";
  // A freeze detector, not the benchmark (its target is 50 ms: docs/BENCHMARKS.md): a UI that
  // waited on the fracture would stall for all of it. Relative, so a loaded CI machine, slow
  // for both, does not fail it.
  EXPECT_LT(stall, took / 2) << "the UI waited on the fracture";
  const auto fragments = w.document()->shown_fragments(slab);
  ASSERT_GE(fragments->size(), 2u);
  w.viewport()->frame_selection();
  save_screenshot(w, "02-slab-fractured.png");

  // The age slider halfway: fewer cracks, meshed in the background from the same simulation.
  const auto state = w.document()->fracture_of(slab);
  w.age_slider()->setValue(w.age_slider()->maximum() / 2);
  EXPECT_LT(w.document()->shown_cracks(slab), state->crack_count());
  run_until([&] { return !w.jobs()->age_running(); });
  int cracks = -1;
  w.document()->shown_fragments(slab, &cracks);
  EXPECT_EQ(cracks, w.document()->shown_cracks(slab));
  save_screenshot(w, "03-half-age.png");
  w.age_slider()->setValue(w.age_slider()->maximum());

  // Undo (Ctrl+Z) makes it whole, redo (Ctrl+Shift+Z) brings the same fragments back.
  QTest::keyClick(&w, Qt::Key_Z, Qt::ControlModifier);
  EXPECT_FALSE(w.document()->fracture_of(slab));
  QTest::keyClick(&w, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
  EXPECT_EQ(w.document()->fracture_of(slab), state);

  // Click a fragment, move it up 0.2 m, explode the rest a little.
  QApplication::processEvents();
  FragmentRef piece;
  for (int y = 0; y < w.viewport()->height() && piece.fragment < 0; y += 5)
    for (int x = 0; x < w.viewport()->width() && piece.fragment < 0; x += 5) {
      const FragmentRef r = w.viewport()->pick(x, y);
      if (r.body == slab && r.fragment >= 0) {
        piece = r;
        QTest::mouseClick(w.viewport(), Qt::LeftButton, {}, QPoint(x, y));
      }
    }
  ASSERT_GE(piece.fragment, 0) << "no fragment of the slab under any pixel";
  ASSERT_TRUE(w.selection()->contains(piece));
  w.edit_selected_fragments([](FragmentEdit& e) { e.offset += Eigen::Vector3d(0, 0.2, 0); }, "Move fragments");
  EXPECT_EQ(w.document()->edit_of(piece).offset.y(), 0.2);
  EXPECT_TRUE(w.selection()->contains(piece)) << "an edit keeps the selection";
  save_screenshot(w, "04-fragment-moved.png");

  // Export, and read it back as a user's tool would (assimp): the slab's fragments, each closed.
  const fs::path out = test::fresh_temp_dir("studio-gui") / "street-studio.glb";
  ASSERT_TRUE(w.export_to(QString::fromStdString(out.string()), false)) << errors.join("\n").toStdString();
  const ImportedScene back = import_scene(out);
  int pieces = 0;
  for (const SceneBody& body : scene_bodies(back)) {
    if (body.path.rfind(slab_path + "/", 0) != 0) continue;
    ++pieces;
    const SceneBodyCheck check = check_scene_body(back, body);
    EXPECT_TRUE(check.fracturable) << body.path << ": " << check.reason;
  }
  EXPECT_EQ(pieces, static_cast<int>(fragments->size()));
  EXPECT_EQ(errors.size(), 2) << errors.join("\n").toStdString();

  // Undo the move and the fracture with a fragment selected: the selection lets go of it, so
  // Delete has nothing to delete and the fracture can still be redone.
  ASSERT_TRUE(w.selection()->contains(piece));
  QTest::keyClick(&w, Qt::Key_Z, Qt::ControlModifier);
  QTest::keyClick(&w, Qt::Key_Z, Qt::ControlModifier);
  EXPECT_FALSE(w.document()->fracture_of(slab));
  EXPECT_FALSE(w.selection()->contains(piece));
  QTest::keyClick(&w, Qt::Key_Delete);
  EXPECT_EQ(errors.size(), 3);
  EXPECT_TRUE(w.document()->undo_stack()->canRedo());
  QTest::keyClick(&w, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
  EXPECT_EQ(w.document()->fracture_of(slab), state);

  // The bathroom (30 bodies), then the street (26) over a selection of the bathroom's last body:
  // the new scene opens with nothing selected.
  ASSERT_TRUE(w.open_file(QString::fromStdString((test::source_dir() / "assets/scenes/bathroom.glb").string())));
  save_screenshot(w, "05-bathroom-opened.png");
  const int last = static_cast<int>(w.document()->bodies().size()) - 1;
  ASSERT_GT(last, 26);
  w.selection()->set({{last, 0, -1}});
  ASSERT_TRUE(w.open_file(QString::fromStdString(street.string())));
  EXPECT_TRUE(w.selection()->empty());
}

}  // namespace
}  // namespace fissure::studio

int main(int argc, char** argv) {
  fissure::studio::use_gl33_core_by_default(0);  // no multisampling: cheaper on llvmpipe, and the test needs none
  QApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
