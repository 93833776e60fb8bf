#include "main_window.hpp"

#include "studio_commands.hpp"

#include "fissure/base/disk_cache.hpp"
#include "fissure/base/error.hpp"
#include "fissure/fracture/fracture_params.hpp"
#include "fissure/fracture/material_file.hpp"
#include "fissure/io/scene_export.hpp"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QSignalBlocker>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QItemSelectionModel>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QSlider>
#include <QStatusBar>
#include <QTableWidget>
#include <QToolBar>
#include <QTreeView>
#include <QVBoxLayout>

#include <algorithm>

namespace fissure::studio {
namespace {

constexpr int kAgeSteps = 1000;
constexpr int kMaxRecent = 8;

template <typename F>
QAction* add_action(QMenu* menu, const QString& text, const QKeySequence& shortcut, F&& f) {
  QAction* a = menu->addAction(text);
  a->setShortcut(shortcut);
  QObject::connect(a, &QAction::triggered, menu, std::forward<F>(f));
  return a;
}

QString what(const std::exception& e) { return QString::fromStdString(e.what()); }

}  // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent), m_jobs(&m_document), m_outliner_model(&m_document) {
  setObjectName("FissureStudio");
  setAcceptDrops(true);
  report_error = [this](const QString& message) { QMessageBox::critical(this, "Fissure Studio", message); };
  m_jobs.set_cache_directory(default_cache_directory());
  m_viewport = new Viewport(&m_document, &m_selection, this);
  setCentralWidget(m_viewport);
  build_docks();
  build_menus();
  build_status();
  resize(1280, 800);

  connect(&m_document, &StudioDocument::scene_reset, this, [this] {
    m_selection.clear();
    const QSignalBlocker block(m_simulation_age);
    m_simulation_age->setValue(m_document.simulation_age().value_or(0.0));
    m_outliner->expandToDepth(2);
    refresh_age_range();
    refresh_title();
    log(QString("Opened %1: %2 bodies").arg(m_document.path()).arg(m_document.bodies().size()));
    for (const std::string& w : m_document.scene().warnings) log("warning: " + QString::fromStdString(w));
  });
  // A fracture undone, an age scrubbed or a fragment deleted: the selection keeps only what is
  // still shown, so no edit lands on fragments that are not on screen.
  auto prune = [this] { m_selection.set(m_document.valid_refs(m_selection.items())); };
  connect(&m_document, &StudioDocument::body_changed, this, [this, prune] {
    prune();
    refresh_age_range();
    refresh_properties();
  });
  connect(&m_document, &StudioDocument::age_changed, this, [this, prune] {
    prune();
    refresh_properties();
  });
  connect(&m_document, &StudioDocument::edits_changed, this, prune);
  connect(&m_document, &StudioDocument::assignments_changed, this, &MainWindow::refresh_properties);
  connect(&m_selection, &Selection::changed, this, [this] {
    refresh_properties();
    sync_outliner_selection();
  });
  connect(m_document.undo_stack(), &QUndoStack::cleanChanged, this, &MainWindow::refresh_title);
  // Queued: the dialog must not open inside initializeGL, with the context current.
  connect(m_viewport, &Viewport::gl_failed, this, [this](const QString& m) { fail("The 3-D view cannot draw: " + m); },
          Qt::QueuedConnection);

  connect(&m_jobs, &StudioJobs::fracture_started, this, [this](int bodies) {
    m_progress->setRange(0, bodies);
    m_progress->setValue(0);
    m_progress->show();
    m_cancel->show();
    m_status->setText(QString("Fracturing %1 %2…").arg(bodies).arg(bodies == 1 ? "body" : "bodies"));
  });
  connect(&m_jobs, &StudioJobs::fracture_progress, this, [this](int done, int total, const QString& path) {
    m_progress->setRange(0, total);
    m_progress->setValue(done);
    m_status->setText(QString("Fractured %1 of %2 (%3)").arg(done).arg(total).arg(path));
  });
  auto job_over = [this](const QString& message) {
    m_progress->hide();
    m_cancel->hide();
    m_status->setText(message.section('\n', 0, 0));
    log(message);
  };
  connect(&m_jobs, &StudioJobs::fracture_finished, this, job_over);
  connect(&m_jobs, &StudioJobs::fracture_cancelled, this, [job_over] { job_over("Fracture cancelled: nothing changed"); });
  connect(&m_jobs, &StudioJobs::fracture_failed, this, [this](const QString& m) {
    m_progress->hide();
    m_cancel->hide();
    m_status->setText("Fracture failed");
    fail(m);  // logs it too
  });
  connect(&m_jobs, &StudioJobs::fracture_refused, this, [this](const QString& m) { fail(m); });
  connect(&m_jobs, &StudioJobs::age_failed, this, [this](const QString& m) { log("Fragments at this age could not be meshed: " + m); });
  refresh_library();
  refresh_title();
}

void MainWindow::build_docks() {
  m_outliner = new QTreeView;
  m_outliner->setModel(&m_outliner_model);
  m_outliner->setSelectionMode(QAbstractItemView::ExtendedSelection);
  m_outliner->header()->setSectionResizeMode(0, QHeaderView::Stretch);
  connect(m_outliner->selectionModel(), &QItemSelectionModel::selectionChanged, this, [this] {
    if (m_syncing_selection) return;
    std::set<FragmentRef> items;
    for (const QModelIndex& index : m_outliner->selectionModel()->selectedRows(0)) {
      const int body = index.data(OutlinerModel::BodyRole).toInt();
      const int fragment = index.data(OutlinerModel::FragmentRole).toInt();
      if (body < 0) continue;
      items.insert(fragment < 0 ? FragmentRef{body, 0, -1} : FragmentRef{body, index.data(OutlinerModel::CracksRole).toInt(), fragment});
    }
    m_syncing_selection = true;
    m_selection.set(items);
    m_syncing_selection = false;
  });
  // Rebuilding a body's fragment rows drops their selection in the view: that is not the
  // artist deselecting, so the studio's selection stays and is shown again after.
  // (The view's selection model hears of removed rows before any slot connected here would.)
  connect(&m_outliner_model, &OutlinerModel::rows_changing, this, [this] { m_syncing_selection = true; });
  connect(&m_outliner_model, &OutlinerModel::rows_changed, this, [this] {
    m_syncing_selection = false;
    sync_outliner_selection();
  });
  auto* outliner_dock = new QDockWidget("Outliner", this);
  outliner_dock->setObjectName("outliner");
  outliner_dock->setWidget(m_outliner);
  addDockWidget(Qt::RightDockWidgetArea, outliner_dock);

  m_properties = new QTableWidget(0, 2);
  m_properties->setHorizontalHeaderLabels({"Property", "Value"});
  m_properties->horizontalHeader()->setSectionResizeMode(1, QHeaderView::Stretch);
  m_properties->verticalHeader()->hide();
  m_properties->setEditTriggers(QAbstractItemView::NoEditTriggers);
  auto* properties_dock = new QDockWidget("Properties", this);
  properties_dock->setObjectName("properties");
  properties_dock->setWidget(m_properties);
  addDockWidget(Qt::RightDockWidgetArea, properties_dock);

  auto* library_panel = new QWidget;
  auto* library_layout = new QVBoxLayout(library_panel);
  m_library = new QListWidget;
  m_library->setToolTip("Fracture materials: double-click assigns one to the selected objects");
  auto* assign_object = new QPushButton("Assign to selected objects");
  auto* assign_material = new QPushButton("Assign to their scene material");
  library_layout->addWidget(m_library);
  library_layout->addWidget(assign_object);
  library_layout->addWidget(assign_material);
  auto current_material = [this] { return m_library->currentItem() ? m_library->currentItem()->data(Qt::UserRole).toString() : QString(); };
  connect(assign_object, &QPushButton::clicked, this, [this, current_material] { assign_to_selection(current_material(), false); });
  connect(assign_material, &QPushButton::clicked, this, [this, current_material] { assign_to_selection(current_material(), true); });
  connect(m_library, &QListWidget::itemDoubleClicked, this,
          [this](QListWidgetItem* item) { assign_to_selection(item->data(Qt::UserRole).toString(), false); });
  auto* library_dock = new QDockWidget("Material library", this);
  library_dock->setObjectName("library");
  library_dock->setWidget(library_panel);
  addDockWidget(Qt::LeftDockWidgetArea, library_dock);

  m_log = new QPlainTextEdit;
  m_log->setReadOnly(true);
  m_log->setMaximumBlockCount(5000);
  auto* log_dock = new QDockWidget("Log", this);
  log_dock->setObjectName("log");
  log_dock->setWidget(m_log);
  addDockWidget(Qt::BottomDockWidgetArea, log_dock);

  auto* time = new QToolBar("Age", this);
  time->setObjectName("age");
  time->addWidget(new QLabel(" Simulate to age "));
  m_simulation_age = new QDoubleSpinBox;
  m_simulation_age->setRange(0.0, 1e6);
  m_simulation_age->setDecimals(2);
  m_simulation_age->setSpecialValueText("material's");  // 0: each material's own age
  m_simulation_age->setToolTip("How long the next fracture simulates (age units); the lowest value uses each material's own age");
  time->addWidget(m_simulation_age);
  connect(m_simulation_age, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [this](double v) {
    m_document.set_simulation_age(v > 0.0 ? std::optional<double>(v) : std::nullopt);
  });
  time->addSeparator();
  time->addWidget(new QLabel(" Age shown "));
  m_age_slider = new QSlider(Qt::Horizontal);
  m_age_slider->setRange(0, kAgeSteps);
  m_age_slider->setValue(kAgeSteps);
  m_age_slider->setMinimumWidth(300);
  m_age_slider->setToolTip("Scrub the crack events: fragments at an earlier age, without simulating again");
  time->addWidget(m_age_slider);
  m_age_label = new QLabel;
  m_age_label->setMinimumWidth(90);
  time->addWidget(m_age_label);
  connect(m_age_slider, &QSlider::valueChanged, this, [this](int v) { set_age_fraction(double(v) / kAgeSteps); });
  time->addSeparator();
  time->addWidget(new QLabel(" Exploded "));
  m_explode_slider = new QSlider(Qt::Horizontal);
  m_explode_slider->setRange(0, 100);
  m_explode_slider->setMaximumWidth(150);
  time->addWidget(m_explode_slider);
  connect(m_explode_slider, &QSlider::valueChanged, this, [this](int v) { m_document.set_explode(v / 100.0); });
  addToolBar(Qt::BottomToolBarArea, time);
}

void MainWindow::build_menus() {
  QMenu* file = menuBar()->addMenu("&File");
  add_action(file, "&Open…", QKeySequence::Open, [this] {
    const QString path = QFileDialog::getOpenFileName(this, "Open a scene or project", {},
                                                      "Scenes and projects (*.glb *.gltf *.fbx *.dae *.obj *.ply *.stl *.off *.json)");
    if (!path.isEmpty()) open_file(path);
  });
  m_recent_menu = file->addMenu("Open &Recent");
  rebuild_recent_menu();
  add_action(file, "&Save Project…", QKeySequence::Save, [this] {
    const QString path = QFileDialog::getSaveFileName(this, "Save the project", {}, "Fissure projects (*.json)");
    if (!path.isEmpty()) save_project_to(path);
  });
  file->addSeparator();
  add_action(file, "&Export Scene…", QKeySequence("Ctrl+E"), [this] {
    const QString path = QFileDialog::getSaveFileName(this, "Export the scene", {}, "Scenes (*.glb *.gltf *.obj *.ply)");
    if (!path.isEmpty()) export_to(path, false);
  });
  file->addAction("Export Selected &Fragments…", this, [this] {
    const QString path = QFileDialog::getSaveFileName(this, "Export the selected fragments", {}, "Scenes (*.glb *.gltf *.obj *.ply)");
    if (!path.isEmpty()) export_to(path, true);
  });
  file->addSeparator();
  add_action(file, "&Quit", QKeySequence::Quit, [this] { close(); });

  QMenu* edit = menuBar()->addMenu("&Edit");
  QAction* undo = m_document.undo_stack()->createUndoAction(this, "&Undo");
  undo->setShortcut(QKeySequence::Undo);
  QAction* redo = m_document.undo_stack()->createRedoAction(this, "&Redo");
  // Not QKeySequence::Redo as well: on Linux it is Ctrl+Shift+Z too, and an ambiguous shortcut fires neither.
  redo->setShortcuts({QKeySequence("Ctrl+Shift+Z"), QKeySequence("Ctrl+Y")});
  edit->addAction(undo);
  edit->addAction(redo);
  edit->addSeparator();
  add_action(edit, "&Hide Selected Fragments", QKeySequence("H"), [this] { edit_selected_fragments([](FragmentEdit& e) { e.hidden = true; }, "Hide fragments"); });
  add_action(edit, "&Show Hidden Fragments", QKeySequence("Alt+H"), [this] {
    std::vector<std::pair<FragmentRef, FragmentEdit>> changes;
    for (int b = 0; b < static_cast<int>(m_document.bodies().size()); ++b) {
      int cracks = 0;
      const auto fragments = m_document.shown_fragments(b, &cracks);
      if (!fragments) continue;
      for (int f = 0; f < static_cast<int>(fragments->size()); ++f) {
        FragmentEdit e = m_document.edit_of({b, cracks, f});
        if (!e.hidden) continue;
        e.hidden = false;
        changes.emplace_back(FragmentRef{b, cracks, f}, e);
      }
    }
    if (!changes.empty()) m_document.undo_stack()->push(new FragmentEditCommand(&m_document, std::move(changes), "Show fragments"));
  });
  add_action(edit, "&Delete Selected Fragments", QKeySequence::Delete, [this] { edit_selected_fragments([](FragmentEdit& e) { e.deleted = true; }, "Delete fragments"); });

  QMenu* fracture = menuBar()->addMenu("F&racture");
  add_action(fracture, "Fracture &Selection", QKeySequence("F"), [this] { fracture_selection(false); });
  add_action(fracture, "Fracture &All of Its Material", QKeySequence("Shift+F"), [this] { fracture_selection(true); });
  add_action(fracture, "&Cancel", QKeySequence("Esc"), [this] { m_jobs.cancel_fracture(); });

  QMenu* view = menuBar()->addMenu("&View");
  add_action(view, "Frame &All", QKeySequence("Home"), [this] { m_viewport->frame_all(); });
  add_action(view, "Frame &Selected", QKeySequence("."), [this] { m_viewport->frame_selection(); });
}

void MainWindow::build_status() {
  m_status = new QLabel;
  statusBar()->addWidget(m_status, 1);
  m_progress = new QProgressBar;
  m_progress->setMaximumWidth(220);
  m_progress->hide();
  statusBar()->addPermanentWidget(m_progress);
  m_cancel = new QPushButton("Cancel");
  m_cancel->hide();
  connect(m_cancel, &QPushButton::clicked, this, [this] { m_jobs.cancel_fracture(); });
  statusBar()->addPermanentWidget(m_cancel);
}

void MainWindow::log(const QString& line) {
  m_log_lines << line;
  m_log->appendPlainText(line);
}

void MainWindow::fail(const QString& message) {
  log("error: " + message);
  if (report_error) report_error(message);
}

bool MainWindow::open_file(const QString& path) {
  // A fracture of the scene open now would be thrown away: stop it instead of letting it run on.
  m_jobs.cancel_fracture();
  try {
    m_document.open(path);
  } catch (const std::exception& e) {
    fail(what(e));
    return false;
  }
  add_recent(QFileInfo(path).absoluteFilePath());
  return true;
}

void MainWindow::assign_to_selection(const QString& material, bool to_scene_material) {
  if (material.isEmpty()) return fail("Choose a material in the library first.");
  const std::vector<int> bodies = m_selection.bodies();
  if (bodies.empty()) return fail("Select the objects to assign " + material + " to (click them in the view or the outliner).");
  std::set<std::string> keys;
  for (int b : bodies) {
    const SceneBody& body = m_document.bodies()[static_cast<std::size_t>(b)];
    if (!to_scene_material) {
      keys.insert(body.path);
      continue;
    }
    for (int m : body.meshes) {
      const int sm = m_document.scene().meshes[static_cast<std::size_t>(m)].material;
      if (sm >= 0) keys.insert(m_document.scene().materials[static_cast<std::size_t>(sm)].name);
    }
  }
  if (keys.empty()) return fail("The selected objects have no scene material: assign the material to the objects instead.");
  QUndoStack* undo = m_document.undo_stack();
  undo->beginMacro(QString("Assign %1").arg(material));
  for (const std::string& key : keys)
    undo->push(new AssignMaterialCommand(&m_document,
                                         to_scene_material ? AssignMaterialCommand::Target::SceneMaterial : AssignMaterialCommand::Target::Node,
                                         key, material.toStdString()));
  undo->endMacro();
  log(QString("Assigned %1 to %2 %3").arg(material).arg(keys.size()).arg(to_scene_material ? "scene material(s)" : "object(s)"));
}

bool MainWindow::fracture_selection(bool all_of_material) {
  std::vector<int> bodies = m_selection.bodies();
  if (all_of_material) {
    std::set<int> all;
    for (int b : bodies)
      for (int other : m_document.bodies_with_material(m_document.material_of(b))) all.insert(other);
    bodies.assign(all.begin(), all.end());
  }
  return m_jobs.fracture(bodies, all_of_material ? "Fracture all of the material" : "Fracture the selection");
}

void MainWindow::edit_selected_fragments(const std::function<void(FragmentEdit&)>& change, const QString& text) {
  for (int b : m_selection.bodies())
    if (m_document.fracture_of(b) && !m_document.shows_its_age(b))
      return fail("The fragments at this age are still being made; edit them once they show.");
  std::vector<std::pair<FragmentRef, FragmentEdit>> changes;
  for (const FragmentRef& r : m_document.valid_refs(m_selection.fragments())) {
    FragmentEdit e = m_document.edit_of(r);
    change(e);
    changes.emplace_back(r, e);
  }
  if (changes.empty()) return fail("Select fragments first (click a fractured object's piece, or pick it in the outliner).");
  m_document.undo_stack()->push(new FragmentEditCommand(&m_document, std::move(changes), text));
  if (text.startsWith("Delete") || text.startsWith("Hide")) m_selection.clear();
}

bool MainWindow::export_to(const QString& path, bool selected_only) {
  try {
    if (!m_document.is_open()) throw InvalidInput("open a scene first");
    const std::set<FragmentRef> chosen = m_document.valid_refs(m_selection.fragments());
    if (selected_only && chosen.empty()) throw InvalidInput("select the fragments to export first");
    const ExportScene scene = m_document.export_scene(selected_only ? &chosen : nullptr);
    write_scene(path.toStdString(), scene);
  } catch (const std::exception& e) {
    fail("Export to " + path + " failed: " + what(e));
    return false;
  }
  log("Exported " + path);
  return true;
}

bool MainWindow::save_project_to(const QString& path) {
  try {
    if (!m_document.is_open()) throw InvalidInput("open a scene first");
    m_document.save_project(path);
  } catch (const std::exception& e) {
    fail("Saving " + path + " failed: " + what(e));
    return false;
  }
  m_document.undo_stack()->setClean();
  log("Saved " + path);
  return true;
}

double MainWindow::max_simulated_age() const {
  double age = 0.0;
  for (int b = 0; b < static_cast<int>(m_document.bodies().size()); ++b)
    if (const auto s = m_document.fracture_of(b)) age = std::max(age, s->fractured.fracture.result.simulated_age);
  return age;
}

void MainWindow::set_age_fraction(double fraction) {
  const double top = max_simulated_age();
  fraction = std::clamp(fraction, 0.0, 1.0);
  // At the top, every body shows its own simulated age (bodies of different materials differ).
  m_document.set_age(fraction >= 1.0 || top <= 0.0 ? std::optional<double>() : std::optional<double>(fraction * top));
  m_age_label->setText(top > 0.0 ? QString("%1 / %2").arg(fraction * top, 0, 'g', 3).arg(top, 0, 'g', 3) : "—");
}

void MainWindow::refresh_age_range() { set_age_fraction(double(m_age_slider->value()) / kAgeSteps); }

void MainWindow::refresh_library() {
  m_library->clear();
  for (const std::string& name : bundled_material_names()) {
    auto* item = new QListWidgetItem(QString::fromStdString(name));
    item->setData(Qt::UserRole, QString::fromStdString(name));
    try {
      item->setToolTip(QString::fromStdString(load_material(find_material(name)).description));
    } catch (const std::exception& e) {
      item->setToolTip("does not load: " + what(e));
      item->setForeground(Qt::red);
    }
    m_library->addItem(item);
  }
}

void MainWindow::refresh_properties() {
  m_properties->setRowCount(0);
  auto row = [this](const QString& key, const QString& value, const QString& tip = {}) {
    const int r = m_properties->rowCount();
    m_properties->insertRow(r);
    auto* k = new QTableWidgetItem(key);
    auto* v = new QTableWidgetItem(value);
    k->setToolTip(tip);
    v->setToolTip(tip);
    m_properties->setItem(r, 0, k);
    m_properties->setItem(r, 1, v);
  };
  const std::vector<int> bodies = m_selection.bodies();
  if (bodies.size() != 1) {
    if (!bodies.empty()) row("Selected", QString("%1 objects").arg(bodies.size()));
    return;
  }
  const int b = bodies.front();
  const SceneBody& body = m_document.bodies()[static_cast<std::size_t>(b)];
  row("Object", QString::fromStdString(body.path));
  const std::string material = m_document.material_of(b);
  row("Fracture material", material.empty() ? "none (it will not break)" : QString::fromStdString(material));
  if (const auto state = m_document.fracture_of(b)) {
    int cracks = 0;
    const auto fragments = m_document.shown_fragments(b, &cracks);
    row("Fragments", QString::number(fragments ? fragments->size() : 0));
    row("Cracks shown", QString("%1 of %2").arg(cracks).arg(state->crack_count()));
    row("Tets", QString::number(state->report.tets));
    row("Seed", QString::number(state->report.seed));
  }
  if (material.empty()) return;
  // The material's parameters, straight from the FractureParams table: the same names, units
  // and ranges as the CLI's flags and the JSON file.
  try {
    const FractureMaterial m = load_material(find_material(material));
    const auto& table = fracture_parameter_table();
    for (std::size_t i = 0; i < table.size(); ++i) {
      const ParameterInfo& p = table[i];
      row(QString::fromUtf8(p.name),
          QString("%1 %2").arg(parameter_value(m.params, i), 0, 'g', 4).arg(QString::fromUtf8(p.unit)),
          QString("%1 (%2; range %3 to %4)").arg(QString::fromUtf8(p.help), QString::fromUtf8(p.flag)).arg(p.min).arg(p.max));
    }
  } catch (const std::exception& e) {
    row("Material", "does not load: " + what(e));
  }
}

void MainWindow::refresh_title() {
  const QString name = m_document.is_open() ? QFileInfo(m_document.path()).fileName() : "no scene";
  setWindowTitle(QString("%1%2 — Fissure Studio").arg(name, m_document.undo_stack()->isClean() ? "" : " *"));
}

void MainWindow::sync_outliner_selection() {
  if (m_syncing_selection) return;
  m_syncing_selection = true;
  QItemSelection chosen;
  for (const FragmentRef& r : m_selection.items()) {
    // (Called while the outliner rebuilds, before the selection is pruned: refs may be stale.)
    if (r.body < 0 || r.body >= static_cast<int>(m_document.bodies().size())) continue;
    QStandardItem* item = m_outliner_model.node_item(m_document.bodies()[static_cast<std::size_t>(r.body)].node);
    if (item && r.fragment >= 0) {
      QStandardItem* row = nullptr;
      for (int c = 0; c < item->rowCount() && !row; ++c) {
        QStandardItem* child = item->child(c);
        if (child->data(OutlinerModel::FragmentRole).toInt() == r.fragment && child->data(OutlinerModel::CracksRole).toInt() == r.cracks)
          row = child;
      }
      item = row;  // none: a fragment not listed now is not shown as its body
    }
    if (item) chosen.select(item->index(), item->index());
  }
  m_outliner->selectionModel()->select(chosen, QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
  m_syncing_selection = false;
}

void MainWindow::add_recent(const QString& path) {
  QSettings settings("Fissure", "Fissure Studio");
  QStringList recent = settings.value("recent").toStringList();
  recent.removeAll(path);
  recent.prepend(path);
  while (recent.size() > kMaxRecent) recent.removeLast();
  settings.setValue("recent", recent);
  rebuild_recent_menu();
}

void MainWindow::rebuild_recent_menu() {
  m_recent_menu->clear();
  const QStringList recent = QSettings("Fissure", "Fissure Studio").value("recent").toStringList();
  for (const QString& path : recent) m_recent_menu->addAction(path, this, [this, path] { open_file(path); });
  m_recent_menu->setEnabled(!recent.isEmpty());
}

void MainWindow::dragEnterEvent(QDragEnterEvent* e) {
  if (e->mimeData()->hasUrls()) e->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* e) {
  for (const QUrl& url : e->mimeData()->urls()) {
    const QString path = url.toLocalFile();
    if (path.isEmpty()) continue;
    // A material file joins the library for this session; anything else is opened as a scene.
    if (path.endsWith(".json", Qt::CaseInsensitive)) {
      try {
        const FractureMaterial m = load_material(path.toStdString());
        auto* item = new QListWidgetItem(QString::fromStdString(m.name) + " (" + QFileInfo(path).fileName() + ")");
        item->setData(Qt::UserRole, path);
        item->setToolTip(QString::fromStdString(m.description));
        m_library->addItem(item);
        log("Added material " + path);
        continue;
      } catch (const std::exception&) {
        // not a material: try it as a project
      }
    }
    open_file(path);
  }
}

void MainWindow::closeEvent(QCloseEvent* e) {
  m_jobs.cancel_fracture();
  e->accept();
}

}  // namespace fissure::studio
