#include "studio_document.hpp"

#include "fissure/base/error.hpp"
#include "fissure/scene/fragment_export.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>

namespace fissure::studio {
namespace fs = std::filesystem;
namespace {

// The centre of volume of fragments: their centres weighted by their volumes.
Eigen::Vector3d centre_of_volume(const std::vector<FragmentMesh>& fragments) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double volume = 0.0;
  for (const FragmentMesh& m : fragments) {
    centre += m.volume * m.centre;
    volume += m.volume;
  }
  return volume > 0.0 ? Eigen::Vector3d(centre / volume) : centre;
}

}  // namespace

StudioDocument::StudioDocument(QObject* parent) : QObject(parent) {}

void StudioDocument::open(const QString& path) {
  const fs::path file = path.toStdString();
  SceneProject project;
  fs::path scene_file = file;
  if (is_scene_project_file(file)) {
    project = read_scene_project(file);
    scene_file = project_path(file, project.scene);
    scene_fracture_options(project, file.string());  // refuses a malformed support or up now, not at the first fracture
  } else {
    project.scene = file.string();
  }
  auto scene = std::make_shared<const ImportedScene>(import_scene(scene_file));  // throws: nothing below runs, nothing changes
  m_scene = std::move(scene);
  m_bodies = scene_bodies(*m_scene);
  m_body_of_node.assign(m_scene->nodes.size(), -1);
  for (std::size_t b = 0; b < m_bodies.size(); ++b) m_body_of_node[static_cast<std::size_t>(m_bodies[b].node)] = static_cast<int>(b);
  m_project = std::move(project);
  m_path = path;
  m_fractures.assign(m_bodies.size(), nullptr);
  m_age.reset();
  m_explode = 0.0;
  m_undo.clear();
  emit scene_reset();
}

Eigen::Vector3d StudioDocument::up() const {
  if (m_project.up) {
    try {
      if (const auto o = scene_fracture_options(m_project, m_path.toStdString()); o.up) return o.up->normalized();
    } catch (const Error&) {
      // open() refused a project whose up does not parse; nothing else sets it
    }
  }
  return m_scene->up;
}

bool StudioDocument::shows_its_age(int body) const {
  int cracks = -1;
  if (!shown_fragments(body, &cracks)) return false;
  return cracks == shown_cracks(body);
}

std::set<FragmentRef> StudioDocument::valid_refs(const std::set<FragmentRef>& refs) const {
  std::set<FragmentRef> out;
  for (const FragmentRef& r : refs) {
    if (r.body < 0 || r.body >= static_cast<int>(m_bodies.size())) continue;
    if (r.fragment < 0) {
      out.insert(r);
      continue;
    }
    int cracks = -1;
    const auto fragments = shown_fragments(r.body, &cracks);
    if (!fragments || cracks != r.cracks || r.fragment >= static_cast<int>(fragments->size()) || edit_of(r).deleted) continue;
    out.insert(r);
  }
  return out;
}

int StudioDocument::body_of_node(int node) const {
  return node >= 0 && node < static_cast<int>(m_body_of_node.size()) ? m_body_of_node[static_cast<std::size_t>(node)] : -1;
}

std::string StudioDocument::material_of(int body) const {
  if (body < 0 || body >= static_cast<int>(m_bodies.size())) return {};
  const std::string* m = body_assignment(*m_scene, m_bodies[static_cast<std::size_t>(body)], m_project.assignments);
  return m ? *m : std::string();
}

std::vector<int> StudioDocument::bodies_with_material(const std::string& material) const {
  std::vector<int> out;
  for (int b = 0; b < static_cast<int>(m_bodies.size()); ++b)
    if (!material.empty() && material_of(b) == material) out.push_back(b);
  return out;
}

namespace {
void set_or_erase(std::map<std::string, std::string>& map, const std::string& key, const std::string& value) {
  if (value.empty()) map.erase(key);
  else map[key] = value;
}
}  // namespace

void StudioDocument::set_material_assignment(const std::string& scene_material, const std::string& material) {
  set_or_erase(m_project.assignments.by_material, scene_material, material);
  emit assignments_changed();
}

void StudioDocument::set_node_assignment(const std::string& path, const std::string& material) {
  set_or_erase(m_project.assignments.by_path, path, material);
  emit assignments_changed();
}

std::shared_ptr<const BodyFractureState> StudioDocument::fracture_of(int body) const {
  if (body < 0 || body >= static_cast<int>(m_fractures.size())) return nullptr;
  return m_fractures[static_cast<std::size_t>(body)];
}

void StudioDocument::set_fracture(int body, std::shared_ptr<BodyFractureState> state) {
  if (body < 0 || body >= static_cast<int>(m_fractures.size())) return;
  m_fractures[static_cast<std::size_t>(body)] = std::move(state);
  emit body_changed(body);
}

std::map<int, std::shared_ptr<BodyFractureState>> StudioDocument::fracture_states(SceneFracture fracture) {
  std::map<int, std::shared_ptr<BodyFractureState>> out;
  for (std::size_t b = 0; b < fracture.results.size(); ++b) {
    if (!fracture.results[b]) continue;
    auto state = std::make_shared<BodyFractureState>();
    state->fractured = std::move(*fracture.results[b]);
    state->report = std::move(fracture.reports[b]);
    const int cracks = state->crack_count();
    auto fragments = std::make_shared<const std::vector<FragmentMesh>>(std::move(state->fractured.fracture.fragments));
    state->fractured.fracture.fragments.clear();
    state->edits[cracks].resize(fragments->size());
    state->centre_at[cracks] = centre_of_volume(*fragments);
    state->fragments_at[cracks] = std::move(fragments);
    out[static_cast<int>(b)] = std::move(state);
  }
  return out;
}

SceneFractureOptions StudioDocument::fracture_options(const std::vector<int>& bodies) const {
  SceneFractureOptions o = scene_fracture_options(m_project, m_path.toStdString());
  o.assignments = {};
  for (int b : bodies) {
    const std::string m = material_of(b);
    if (!m.empty()) o.assignments.by_path[m_bodies[static_cast<std::size_t>(b)].path] = m;
  }
  // Setups of bodies outside this job would be warned about as matching nothing.
  std::map<std::string, SceneBodySetup> setups;
  for (const auto& [path, material] : o.assignments.by_path)
    if (auto it = o.body_setups.find(path); it != o.body_setups.end()) setups.insert(*it);
  o.body_setups = std::move(setups);
  o.slice = o.slices = 1;
  o.strict = false;
  o.keep_meshes = true;  // the age slider re-meshes fragments from them
  return o;
}

void StudioDocument::set_age(std::optional<double> age) {
  if (age == m_age) return;
  m_age = age;
  emit age_changed();
}

void StudioDocument::set_simulation_age(std::optional<double> age) {
  if (age && !(*age >= 0.0 && std::isfinite(*age))) throw InvalidInput("the age to simulate must be a finite number ≥ 0");
  m_project.age = age;
}

int StudioDocument::shown_cracks(int body) const {
  const auto state = fracture_of(body);
  if (!state) return 0;
  if (!m_age) return state->crack_count();
  return state->fractured.fracture.result.crack_count_at(*m_age);
}

std::shared_ptr<const std::vector<FragmentMesh>> StudioDocument::shown_fragments(int body, int* cracks) const {
  const auto state = fracture_of(body);
  if (!state || state->fragments_at.empty()) return nullptr;
  const int want = shown_cracks(body);
  // The meshed count nearest to the one wanted (ties: the lower), until the age job brings it.
  const auto& at = state->fragments_at;
  auto best = at.lower_bound(want);
  if (best == at.end()) best = std::prev(best);
  else if (best->first != want && best != at.begin() && want - std::prev(best)->first <= best->first - want) best = std::prev(best);
  if (cracks) *cracks = best->first;
  return best->second;
}

void StudioDocument::add_fragments(int body, const BodyFractureState* of, int cracks,
                                   std::shared_ptr<const std::vector<FragmentMesh>> fragments) {
  if (body < 0 || body >= static_cast<int>(m_fractures.size())) return;
  BodyFractureState* state = m_fractures[static_cast<std::size_t>(body)].get();
  if (!state || state != of) return;  // the body was fractured again or undone meanwhile
  if (state->fragments_at.count(cracks)) return;
  state->edits[cracks].resize(fragments->size());
  state->centre_at[cracks] = centre_of_volume(*fragments);
  state->fragments_at[cracks] = std::move(fragments);
  emit body_changed(body);
}

void StudioDocument::mark_failed(int body, const BodyFractureState* of, int cracks) {
  if (body < 0 || body >= static_cast<int>(m_fractures.size())) return;
  BodyFractureState* state = m_fractures[static_cast<std::size_t>(body)].get();
  if (state && state == of) state->failed_counts.insert(cracks);
}

FragmentEdit StudioDocument::edit_of(const FragmentRef& f) const {
  const auto state = fracture_of(f.body);
  if (!state) return {};
  const auto it = state->edits.find(f.cracks);
  if (it == state->edits.end() || f.fragment < 0 || f.fragment >= static_cast<int>(it->second.size())) return {};
  return it->second[static_cast<std::size_t>(f.fragment)];
}

void StudioDocument::set_edit(const FragmentRef& f, const FragmentEdit& e) {
  if (f.body < 0 || f.body >= static_cast<int>(m_fractures.size())) return;
  BodyFractureState* state = m_fractures[static_cast<std::size_t>(f.body)].get();
  if (!state) return;
  auto& edits = state->edits[f.cracks];
  if (f.fragment < 0) return;
  if (f.fragment >= static_cast<int>(edits.size())) edits.resize(static_cast<std::size_t>(f.fragment) + 1);
  edits[static_cast<std::size_t>(f.fragment)] = e;
  emit edits_changed(f.body);
}

void StudioDocument::set_explode(double factor) {
  factor = std::clamp(std::isfinite(factor) ? factor : 0.0, 0.0, 10.0);
  if (factor == m_explode) return;
  m_explode = factor;
  emit explode_changed();
}

Eigen::Vector3d StudioDocument::drawn_offset(const FragmentRef& f) const {
  Eigen::Vector3d offset = edit_of(f).offset;
  if (m_explode <= 0.0) return offset;
  const auto state = fracture_of(f.body);
  if (!state) return offset;
  const auto it = state->fragments_at.find(f.cracks);
  if (it == state->fragments_at.end() || f.fragment < 0 || f.fragment >= static_cast<int>(it->second->size())) return offset;
  const auto centre = state->centre_at.find(f.cracks);
  if (centre == state->centre_at.end()) return offset;
  return offset + m_explode * ((*it->second)[static_cast<std::size_t>(f.fragment)].centre - centre->second);
}

namespace {

// A fragment moved by `offset`: its vertices and centre (the rest is translation-invariant).
FragmentMesh moved(FragmentMesh m, const Eigen::Vector3d& offset) {
  m.vertices.rowwise() += offset.transpose();
  m.centre += offset;
  return m;
}

// The fragments kept (in order) and their contacts renumbered among them.
std::vector<FragmentMesh> kept_fragments(const std::vector<FragmentMesh>& all, const std::vector<FragmentEdit>& edits,
                                         const std::vector<char>& keep) {
  std::vector<int> index(all.size(), -1);
  int next = 0;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (keep[i]) index[i] = next++;
  std::vector<FragmentMesh> out;
  out.reserve(static_cast<std::size_t>(next));
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (!keep[i]) continue;
    FragmentMesh m = moved(all[i], i < edits.size() ? edits[i].offset : Eigen::Vector3d::Zero());
    std::vector<FragmentContact> contacts;
    for (const FragmentContact& c : m.contacts)
      if (c.fragment >= 0 && c.fragment < static_cast<int>(index.size()) && index[static_cast<std::size_t>(c.fragment)] >= 0)
        contacts.push_back({index[static_cast<std::size_t>(c.fragment)], c.area});
    m.contacts = std::move(contacts);
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace

ExportScene StudioDocument::export_scene(const std::set<FragmentRef>* only) const {
  SceneFracture fracture;
  fracture.bodies = m_bodies;
  fracture.reports.resize(m_bodies.size());
  fracture.results.resize(m_bodies.size());
  const SceneFractureOptions options = scene_fracture_options(m_project, m_path.toStdString());
  fracture.up = (options.up ? *options.up : m_scene->up).normalized();
  fracture.unit = m_project.unit;
  for (std::size_t b = 0; b < m_bodies.size(); ++b) {
    fracture.reports[b].path = m_bodies[b].path;
    const auto state = m_fractures[b];
    if (!state) continue;
    int cracks = 0;
    const auto fragments = shown_fragments(static_cast<int>(b), &cracks);
    const auto edits_it = state->edits.find(cracks);
    const std::vector<FragmentEdit> no_edits;
    const std::vector<FragmentEdit>& edits = edits_it == state->edits.end() ? no_edits : edits_it->second;
    std::vector<char> keep(fragments->size(), 1);
    for (std::size_t i = 0; i < keep.size(); ++i) {
      if (i < edits.size() && edits[i].deleted) keep[i] = 0;
      if (only && !only->count({static_cast<int>(b), cracks, static_cast<int>(i)})) keep[i] = 0;
    }
    fracture.reports[b] = state->report;
    FracturedSceneBody body = state->fractured;
    body.fracture.fragments = kept_fragments(*fragments, edits, keep);
    fracture.results[b] = std::move(body);
  }
  if (!only) return scene_export(*m_scene, fracture);

  // Just the chosen fragments: each body's, as fragment_scene() writes a body's, side by side
  // in world coordinates (the scene's units, so they line up with it), their names prefixed
  // with their body's node name.
  ExportScene out;
  out.up = fracture.up;
  out.frame_name = "fragments";
  std::map<std::string, int> material_index;
  for (std::size_t b = 0; b < m_bodies.size(); ++b) {
    if (!fracture.results[b] || fracture.results[b]->fracture.fragments.empty()) continue;
    const FracturedSceneBody& body = *fracture.results[b];
    ExportScene part_scene = fragment_scene(body.fracture.fragments, body.fracture.result.cracks, body.fracture.params.density,
                                            body.appearance);
    std::vector<int> remap;
    for (const ExportMaterial& m : part_scene.materials) {
      auto [it, inserted] = material_index.emplace(m.name, static_cast<int>(out.materials.size()));
      if (inserted) out.materials.push_back(m);
      remap.push_back(it->second);
    }
    const int base = static_cast<int>(out.parts.size());
    const std::string prefix = m_scene->nodes[static_cast<std::size_t>(m_bodies[b].node)].name + ".";
    const double to_scene = 1.0 / m_project.unit;  // fragments are in metres; the file in the scene's units
    for (ExportPart p : part_scene.parts) {
      p.name = prefix + p.name;
      p.translation *= to_scene;
      p.vertices *= to_scene;
      if (p.parent >= 0) p.parent += base;
      for (int& m : p.triangle_material) m = remap[static_cast<std::size_t>(m)];
      out.parts.push_back(std::move(p));
    }
  }
  return out;
}

void StudioDocument::save_project(const QString& file) {
  const fs::path target = file.toStdString();
  SceneProject p = m_project;
  // The scene relative to the project's folder when it can be, so the pair moves together.
  const fs::path scene = is_scene_project_file(m_path.toStdString()) ? project_path(m_path.toStdString(), m_project.scene)
                                                                      : fs::path(m_path.toStdString());
  std::error_code ec;
  const fs::path absolute_scene = fs::absolute(scene, ec);
  const fs::path folder = fs::absolute(target, ec).parent_path();
  const fs::path relative = absolute_scene.lexically_relative(folder);
  p.scene = !relative.empty() && *relative.begin() != ".." ? relative.string() : absolute_scene.string();
  write_scene_project(target, p);
}

}  // namespace fissure::studio
