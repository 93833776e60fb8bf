#pragma once
// Fissure Studio's main window: the viewport in the middle; docked outliner, properties,
// material library and log; the age and exploded-view sliders; menus and keys that follow
// Blender where it has a habit. Every edit goes through the document's undo stack, every core
// call through StudioJobs, so the window never waits on the core.
#include "outliner_model.hpp"
#include "selection.hpp"
#include "studio_document.hpp"
#include "studio_jobs.hpp"
#include "viewport.hpp"

#include <QMainWindow>

#include <functional>

class QDoubleSpinBox;
class QLabel;
class QListWidget;
class QPlainTextEdit;
class QProgressBar;
class QPushButton;
class QSlider;
class QTableWidget;
class QTreeView;
class QMenu;

namespace fissure::studio {

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(QWidget* parent = nullptr);

  StudioDocument* document() { return &m_document; }
  Selection* selection() { return &m_selection; }
  StudioJobs* jobs() { return &m_jobs; }
  Viewport* viewport() { return m_viewport; }
  QTreeView* outliner() { return m_outliner; }
  QListWidget* library() { return m_library; }
  QSlider* age_slider() { return m_age_slider; }
  QDoubleSpinBox* simulation_age() { return m_simulation_age; }

  /// Opens a scene or project; a failure is reported (a dialog) and leaves what is open.
  bool open_file(const QString& path);
  /// Assigns the library's material `material` to the selected bodies (by node) or, with
  /// `to_scene_material`, to their scene materials, as one undo step.
  void assign_to_selection(const QString& material, bool to_scene_material);
  /// Fractures the selected bodies, or every body of the selection's fracture materials.
  bool fracture_selection(bool all_of_material);
  /// Hides, shows or deletes the selected fragments, or moves them by `offset`; one undo step.
  void edit_selected_fragments(const std::function<void(FragmentEdit&)>& change, const QString& text);
  /// Writes the scene as shown (or just the selected fragments); false after reporting a failure.
  bool export_to(const QString& path, bool selected_only);
  bool save_project_to(const QString& path);
  /// The age slider as an age: its position × the largest simulated age / its range.
  void set_age_fraction(double fraction);

  /// Where failures go: a modal dialog unless a test puts its own in.
  std::function<void(const QString&)> report_error;
  /// The messages the log dock shows, also for tests.
  QStringList log_lines() const { return m_log_lines; }

 protected:
  void dragEnterEvent(QDragEnterEvent* e) override;
  void dropEvent(QDropEvent* e) override;
  void closeEvent(QCloseEvent* e) override;

 private:
  void build_menus();
  void build_docks();
  void build_status();
  void log(const QString& line);
  void fail(const QString& message);
  void refresh_library();
  void refresh_properties();
  void refresh_age_range();
  void refresh_title();
  void sync_outliner_selection();
  void add_recent(const QString& path);
  void rebuild_recent_menu();
  double max_simulated_age() const;

  StudioDocument m_document;
  Selection m_selection;
  StudioJobs m_jobs;
  OutlinerModel m_outliner_model;
  Viewport* m_viewport = nullptr;
  QTreeView* m_outliner = nullptr;
  QListWidget* m_library = nullptr;
  QTableWidget* m_properties = nullptr;
  QPlainTextEdit* m_log = nullptr;
  QDoubleSpinBox* m_simulation_age = nullptr;
  QSlider* m_age_slider = nullptr;
  QLabel* m_age_label = nullptr;
  QSlider* m_explode_slider = nullptr;
  QProgressBar* m_progress = nullptr;
  QPushButton* m_cancel = nullptr;
  QLabel* m_status = nullptr;
  QMenu* m_recent_menu = nullptr;
  QStringList m_log_lines;
  bool m_syncing_selection = false;
};

}  // namespace fissure::studio
