#pragma once
// What the studio has open: a scene read by the scene module, its fracture assignments and
// project settings (the scene module's project file, so the CLI repeats a studio session), the
// bodies fractured so far, and the artist's edits of their fragments. Every edit goes through
// the document's QUndoStack (studio_commands.hpp); views listen to its signals and never
// change it directly.
#include "fissure/io/scene_import.hpp"
#include "fissure/scene/scene_fracture.hpp"
#include "fissure/scene/scene_project.hpp"

#include <QObject>
#include <QString>
#include <QUndoStack>

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace fissure::studio {

/// What the artist did to one fragment.
struct FragmentEdit {
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  ///< moved by, world frame, m (as fragments are)
  bool hidden = false;   ///< not drawn; still exported
  bool deleted = false;  ///< neither drawn nor exported
  bool operator==(const FragmentEdit& o) const { return offset == o.offset && hidden == o.hidden && deleted == o.deleted; }
};

/// One fractured body: the simulation's result (fragments at its simulated age) and, for each
/// crack count the age slider has shown, the fragments then and the edits made to them.
struct BodyFractureState {
  FracturedSceneBody fractured;
  SceneBodyReport report;
  /// Fragments by crack count (result.crack_count_at(age)); the simulated age's is filled in
  /// at once, the others by the age job when the slider first reaches them.
  std::map<int, std::shared_ptr<const std::vector<FragmentMesh>>> fragments_at;
  std::map<int, std::vector<FragmentEdit>> edits;  ///< by crack count, one per fragment
  /// By crack count, the fragments' centre of volume (the exploded view pushes from it), set
  /// with fragments_at so a frame does not sum every fragment for each one it draws.
  std::map<int, Eigen::Vector3d> centre_at;
  std::set<int> failed_counts;  ///< crack counts whose fragments could not be meshed (not retried)
  int crack_count() const { return static_cast<int>(fractured.fracture.result.cracks.size()); }
};

/// A fragment, as selections and commands name it.
struct FragmentRef {
  int body = -1;
  int cracks = 0;    ///< the crack count it belongs to
  int fragment = -1;
  auto operator<=>(const FragmentRef&) const = default;
};

class StudioDocument : public QObject {
  Q_OBJECT
 public:
  explicit StudioDocument(QObject* parent = nullptr);

  /// Reads a scene (glTF, GLB, FBX, DAE, OBJ, PLY, STL, OFF) or a project (.json) and replaces
  /// what is open. Throws fissure::Error naming the file; on a throw nothing open changes.
  void open(const QString& path);
  bool is_open() const { return !m_scene->nodes.empty(); }
  const QString& path() const { return m_path; }
  const ImportedScene& scene() const { return *m_scene; }
  /// Shared with background jobs, which read it while the artist goes on.
  std::shared_ptr<const ImportedScene> scene_ptr() const { return m_scene; }
  const std::vector<SceneBody>& bodies() const { return m_bodies; }
  /// The body of node `node`, or -1.
  int body_of_node(int node) const;

  const SceneProject& project() const { return m_project; }
  /// The scene's up axis as fractures take it (the project's "up", else the format's).
  Eigen::Vector3d up() const;
  /// Metres per scene unit (the project's "unit"): fragments are in metres, the scene in its units.
  double unit() const { return m_project.unit; }
  QUndoStack* undo_stack() { return &m_undo; }

  // --- assignments (set through AssignMaterialCommand) ---
  /// The fracture material `body` gets (its node's, an ancestor's, or its scene material's), or "".
  std::string material_of(int body) const;
  /// The bodies that material_of() gives `material`.
  std::vector<int> bodies_with_material(const std::string& material) const;
  void set_material_assignment(const std::string& scene_material, const std::string& material);  ///< "" removes
  void set_node_assignment(const std::string& path, const std::string& material);               ///< "" removes

  // --- fracture results (set through ApplyFractureCommand) ---
  std::shared_ptr<const BodyFractureState> fracture_of(int body) const;
  void set_fracture(int body, std::shared_ptr<BodyFractureState> state);
  /// The results of a job as states for ApplyFractureCommand: every fractured body's (its
  /// fragments move into fragments_at, leaving fractured.fracture.fragments empty).
  static std::map<int, std::shared_ptr<BodyFractureState>> fracture_states(SceneFracture fracture);
  /// The options a fracture job runs with for `bodies`: the project's, with each body assigned
  /// by its path to its material, so its seed and result are those of a whole-scene CLI run.
  SceneFractureOptions fracture_options(const std::vector<int>& bodies) const;

  /// The age fractures simulate to (the project's "age"); unset: each material's own.
  std::optional<double> simulation_age() const { return m_project.age; }
  void set_simulation_age(std::optional<double> age);

  // --- age shown (view state, not an undo step, as a timeline frame is not) ---
  /// The age shown; unset: each body's simulated age.
  std::optional<double> age() const { return m_age; }
  void set_age(std::optional<double> age);
  /// The crack count shown for a fractured body at the current age.
  int shown_cracks(int body) const;
  /// The fragments shown for a fractured body (null: not fractured). When the age's fragments
  /// are not meshed yet, the nearest meshed crack count's, until add_fragments() brings them.
  std::shared_ptr<const std::vector<FragmentMesh>> shown_fragments(int body, int* cracks = nullptr) const;
  /// True when the fragments shown for `body` are those of the age shown (not a stand-in
  /// while the age job meshes them).
  bool shows_its_age(int body) const;
  /// The refs of `refs` that name a fragment shown now (its body fractured, its crack count the
  /// one shown, not deleted) or a body of this scene.
  std::set<FragmentRef> valid_refs(const std::set<FragmentRef>& refs) const;
  /// Stores fragments the age job meshed (kept while the body's result stays the same).
  void add_fragments(int body, const BodyFractureState* of, int cracks, std::shared_ptr<const std::vector<FragmentMesh>> fragments);
  /// Notes that the age job could not mesh `cracks` for the body's current result `of`.
  void mark_failed(int body, const BodyFractureState* of, int cracks);

  // --- fragment edits (set through FragmentEditCommand) ---
  FragmentEdit edit_of(const FragmentRef& f) const;
  void set_edit(const FragmentRef& f, const FragmentEdit& e);
  /// Pushes fragments out of their body's centre by `factor` of their distance (0: together).
  double explode() const { return m_explode; }
  void set_explode(double factor);
  /// Where fragment f is drawn: its edit's offset plus the exploded view's push, in metres.
  Eigen::Vector3d drawn_offset(const FragmentRef& f) const;

  // --- export ---
  /// The scene as shown: every fractured body's fragments at the shown age, moved as edited,
  /// deleted ones left out (hidden ones kept). With `only`, just those fragments, as parts of
  /// their own (their body's world transform baked in).
  ExportScene export_scene(const std::set<FragmentRef>* only = nullptr) const;
  /// Writes the project (the scene module's JSON) to `file`, atomically.
  void save_project(const QString& file);

 signals:
  void scene_reset();               ///< a new scene is open
  void assignments_changed();
  void body_changed(int body);      ///< its fracture or its fragments changed
  void edits_changed(int body);     ///< an edit of its fragments changed (geometry is the same)
  void age_changed();
  void explode_changed();

 private:
  std::shared_ptr<const ImportedScene> m_scene = std::make_shared<const ImportedScene>();
  std::vector<SceneBody> m_bodies;
  std::vector<int> m_body_of_node;
  SceneProject m_project;
  QString m_path;
  std::vector<std::shared_ptr<BodyFractureState>> m_fractures;
  std::optional<double> m_age;
  double m_explode = 0.0;
  QUndoStack m_undo;
};

}  // namespace fissure::studio
