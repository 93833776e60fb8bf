#include "fissure/scene/scene_fracture.hpp"

#include "fissure/base/content_hash.hpp"
#include "fissure/base/disk_cache.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/parallel.hpp"
#include "fissure/mesh/tet_mesh_cache.hpp"
#include "fissure/scene/body_facing.hpp"
#include "fissure/scene/fragment_export.hpp"
#include "fissure/scene/scene_body_check.hpp"
#include "fissure/scene/scene_merge.hpp"

#include <nlohmann/json.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <set>

namespace fissure {
namespace {

std::vector<std::string> unmatched_assignments(const ImportedScene& scene, const std::vector<SceneBody>& bodies,
                                               const SceneAssignments& a) {
  std::vector<std::string> warnings;
  std::set<std::string> material_names, paths;
  for (const SceneMaterial& m : scene.materials) material_names.insert(m.name);
  for (const SceneNode& n : scene.nodes) paths.insert(n.path);
  for (const auto& [name, material] : a.by_material) {
    if (material_names.count(name)) continue;
    std::string list;
    for (const std::string& n : material_names) list += (list.empty() ? "" : ", ") + n;
    warnings.push_back("assignment " + name + "=" + material + ": the scene has no material " + name + " (it has: " +
                       (list.empty() ? std::string("none") : list) + ")");
  }
  for (const auto& [path, material] : a.by_path) {
    if (!paths.count(path)) warnings.push_back("assignment " + path + "=" + material + ": the scene has no node " + path);
  }
  return warnings;
}

std::vector<std::string> unmatched_setups(const std::vector<SceneBody>& bodies, const std::map<std::string, SceneBodySetup>& setups) {
  std::set<std::string> paths;
  for (const SceneBody& b : bodies) paths.insert(b.path);
  std::vector<std::string> warnings;
  for (const auto& [path, setup] : setups) {
    if (!paths.count(path)) warnings.push_back("loads and supports for " + path + ": the scene has no body " + path);
  }
  return warnings;
}

// The run's identity (SceneFracture::run): everything that decides its output but the slice.
std::string run_identity(const ImportedScene& scene, const SceneFractureOptions& o) {
  ContentHasher h;
  // v2: standing plates are struck on their face (body_facing.hpp); v3: an unfitted material's
  // load is drawn per body (drawn_load()). Slices of earlier versions do not mix in.
  h.add("fissure scene run v3").add(scene.up);
  for (const SceneNode& n : scene.nodes) {
    h.add(n.path).add(static_cast<std::int64_t>(n.parent)).add(n.local);
    for (int m : n.meshes) h.add(static_cast<std::int64_t>(m));
  }
  for (const SceneMesh& m : scene.meshes) h.add(m.name).add(m.vertices).add(m.triangles).add(m.uvs).add(static_cast<std::int64_t>(m.material));
  for (const SceneMaterial& m : scene.materials) {
    h.add(m.name).add(m.colour);
    for (const std::string& t : m.textures) h.add(t);
  }
  for (const auto& [k, v] : o.assignments.by_material) h.add("material").add(k).add(v);
  for (const auto& [k, v] : o.assignments.by_path) h.add("path").add(k).add(v);
  for (const auto& [path, setup] : o.body_setups) {
    h.add("setup").add(path).add(static_cast<std::int64_t>(setup.free_body));
    for (const PatchLoad& l : setup.loads) h.add("load").add(l.position).add(l.normal).add(l.magnitude).add(l.radius);
    for (const SupportSpec& s : setup.supports) h.add("support").add(s.spec);
    if (setup.up) h.add("up").add(*setup.up);
  }
  h.add(static_cast<std::int64_t>(o.seed)).add(o.age ? *o.age : -1.0).add(static_cast<std::int64_t>(o.target_tets));
  h.add(o.up ? Eigen::Vector3d(*o.up) : Eigen::Vector3d::Zero());
  if (o.unit != 1.0) h.add("unit").add(o.unit);  // absent at 1, so runs before --unit keep their identity
  return h.finish().hex();
}

}  // namespace

const char* status_name(SceneBodyReport::Status status) {
  switch (status) {
    case SceneBodyReport::Status::Fractured: return "fractured";
    case SceneBodyReport::Status::Skipped: return "skipped";
    case SceneBodyReport::Status::Unassigned: return "unassigned";
    case SceneBodyReport::Status::OtherSlice: return "other slice";
  }
  return "unknown";
}

std::uint64_t body_seed(std::uint64_t project_seed, const std::string& path) {
  return ContentHasher().add("fissure body seed").add(static_cast<std::int64_t>(project_seed)).add(path).finish().lo;
}

SceneFracture fracture_scene(const ImportedScene& scene, const SceneFractureOptions& options) {
  if (options.slices < 1 || options.slice < 1 || options.slice > options.slices) {
    throw InvalidInput("--bodies " + std::to_string(options.slice) + "/" + std::to_string(options.slices) +
                       ": K must be in 1..N");
  }
  if (!(options.unit > 0.0) || !std::isfinite(options.unit) || options.unit < 1e-9 || options.unit > 1e9) {
    throw InvalidInput("--unit " + format_number(options.unit) + ": metres per scene unit must be a positive number (0.01 for centimetres)");
  }
  SceneFracture out;
  out.unit = options.unit;
  out.slice = options.slice;
  out.slices = options.slices;
  out.run = run_identity(scene, options);
  out.bodies = scene_bodies(scene);
  out.warnings = scene.warnings;  // what the import could not use (an OBJ's missing .mtl)
  for (std::string& w : unmatched_assignments(scene, out.bodies, options.assignments)) out.warnings.push_back(std::move(w));
  for (std::string& w : unmatched_setups(out.bodies, options.body_setups)) out.warnings.push_back(std::move(w));
  out.reports.resize(out.bodies.size());
  out.results.resize(out.bodies.size());

  // Every assigned material, each file loaded once and before any work: a misspelt name or a
  // missing file is one error for the run, not a skip for each of its bodies.
  std::map<std::string, std::shared_ptr<const FractureMaterial>> materials;
  const auto load_assigned = [&](const std::string& key, const std::string& material) {
    if (materials.count(material)) return;
    const std::string what = "assignment " + key + "=" + material + ": ";
    try {
      materials[material] = std::make_shared<const FractureMaterial>(load_material(find_material(material)));
    } catch (const IoError& e) {
      throw IoError(what + e.what());
    } catch (const InvalidInput& e) {
      throw InvalidInput(what + e.what());
    }
  };
  for (const auto& [name, material] : options.assignments.by_material) load_assigned(name, material);
  for (const auto& [path, material] : options.assignments.by_path) load_assigned(path, material);

  // The bodies of this slice.
  std::vector<std::size_t> work;
  int assigned = 0;
  for (std::size_t b = 0; b < out.bodies.size(); ++b) {
    SceneBodyReport& report = out.reports[b];
    report.path = out.bodies[b].path;
    const std::string* assignment = body_assignment(scene, out.bodies[b], options.assignments);
    if (!assignment) continue;  // Unassigned: nothing about it is computed
    report.material = *assignment;
    report.seed = body_seed(options.seed, report.path);
    if (assigned++ % options.slices != options.slice - 1) {
      report.status = SceneBodyReport::Status::OtherSlice;
      continue;
    }
    report.material_name = materials[*assignment]->name;
    work.push_back(b);
  }

  const Eigen::Vector3d up = (options.up ? *options.up : scene.up).normalized();
  out.up = up;
  // Which way a standing plate faces: towards the middle of the whole scene, fractured or not.
  const Eigen::Vector3d centre = work.empty() ? Eigen::Vector3d::Zero() : scene_centre(scene, out.bodies);
  const std::uint64_t cache_cap = options.cache_max_bytes > 0 ? options.cache_max_bytes : default_cache_size_limit();
  // Each body's closedness check, made first for all of them under `strict` (so a body that
  // would be skipped fails the run before any meshing), else inside each body's work.
  std::vector<std::optional<SceneBodyCheck>> checks(work.size());
  if (options.strict) {
    if (!out.warnings.empty()) throw InvalidInput("--strict: " + out.warnings.front());
    parallel_for_dynamic(work.size(), options.threads,
                         [&](std::size_t w) { checks[w] = check_scene_body(scene, out.bodies[work[w]]); });
    for (std::size_t w = 0; w < work.size(); ++w)
      if (!checks[w]->fracturable)
        throw InvalidInput("--strict: " + out.bodies[work[w]].path + " is not fracturable: " + checks[w]->reason);
  }
  std::mutex done_mutex;
  int done = 0;
  // A cache that cannot be written is said once per kind (tet meshes, stress fields), as the
  // first body in scene order met it, so the warnings do not depend on the thread schedule.
  std::vector<std::string> mesh_cache_warnings(out.bodies.size()), stress_cache_warnings(out.bodies.size());
  parallel_for_dynamic(work.size(), options.threads, [&](std::size_t w) {
    const std::size_t b = work[w];
    SceneBodyReport& report = out.reports[b];
    try {
      SceneBodyCheck check = checks[w] ? std::move(*checks[w]) : check_scene_body(scene, out.bodies[b]);
      report.repairs = check.repairs;
      if (!check.fracturable) throw InvalidInput(check.reason);
      const auto setup = options.body_setups.find(report.path);
      report.up = setup != options.body_setups.end() && setup->second.up ? *setup->second.up
                                                                          : body_facing(check.world.vertices, up, centre);
      if (options.unit != 1.0) {
        check.world.vertices *= options.unit;
        check.world.appearance.corners *= options.unit;
      }
      BodyFractureRequest request;
      FracturedSceneBody done_body;
      done_body.appearance = check.world.appearance;
      done_body.scene_materials = check.scene_materials;
      request.surface = std::move(check.world);
      request.material = *materials.at(report.material);
      request.up = report.up;
      request.seed = report.seed;
      request.age = options.age;
      request.target_tets = options.target_tets;
      request.memory_limit_bytes = options.memory_limit_bytes;
      request.keep_mesh = options.keep_meshes;
      if (setup != options.body_setups.end()) {
        request.patch_loads = setup->second.loads;
        request.supports = setup->second.supports;
        for (PatchLoad& l : request.patch_loads) {
          l.position *= options.unit;
          l.radius *= options.unit;
        }
        for (SupportSpec& s : request.supports) {
          s.selection.box *= options.unit;
          s.selection.center *= options.unit;
          s.selection.radius *= options.unit;
        }
        request.free_body = setup->second.free_body;
      }
      Mesher mesher = options.mesher;
      if (!mesher && !options.cache_dir.empty()) {
        mesher = [&](const SurfaceMesh& surface, const TetrahedralizeOptions& o) {
          TetMeshCacheResult r = cached_tetrahedralize(surface, o, options.cache_dir, cache_cap, options.cancel);
          report.mesh_cached = r.loaded;
          mesh_cache_warnings[b] = std::move(r.warning);
          return std::move(r.mesh);
        };
      }
      done_body.fracture = fracture_body_surface(request, 1, mesher, options.cancel, {options.cache_dir, cache_cap});
      const BodyFracture& result = done_body.fracture;
      report.stress_cached = result.stress_cached;
      stress_cache_warnings[b] = result.cache_warning;
      report.status = SceneBodyReport::Status::Fractured;
      report.fragments = static_cast<int>(result.fragments.size());
      report.tets = result.tets;
      for (const LoadSpec& l : result.loads) report.loads.push_back(l.spec);
      report.seconds = result.seconds;
      out.results[b] = std::move(done_body);
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      report.status = SceneBodyReport::Status::Skipped;
      report.reason = e.what();
    }
    if (options.on_body_done) {
      const std::lock_guard<std::mutex> lock(done_mutex);
      options.on_body_done(++done, static_cast<int>(work.size()), report.path);
    }
  });
  for (const auto* kind : {&mesh_cache_warnings, &stress_cache_warnings}) {
    const auto first = std::find_if(kind->begin(), kind->end(), [](const std::string& w) { return !w.empty(); });
    if (first != kind->end()) out.warnings.push_back(*first);
  }
  for (const std::size_t b : work) {
    const SceneBodyReport& r = out.reports[b];
    if (r.status != SceneBodyReport::Status::Fractured) continue;
    if (!out.results[b]->fracture.overload.empty()) out.warnings.push_back(r.path + ": " + out.results[b]->fracture.overload);
    // 1.5×: the mesher's own count tolerance is far tighter; this is a body that needed more
    // (than --tets, or the default it stood for: a 4 mm mirror took 92K for 6000).
    const int asked = out.results[b]->fracture.tets_asked;
    if (asked > 0 && r.tets > 1.5 * asked) {
      out.notes.push_back(r.path + ": meshed with " + std::to_string(r.tets) + " tets, not the " + std::to_string(asked) +
                          (options.target_tets > 0 ? " asked for" : " of the default") +
                          ": elements larger than a thin body's thickness would leave it hollow");
    }
    if (r.fragments <= 1) {
      out.notes.push_back(r.path + ": no crack separated a piece, so it stays whole (" +
                          format_number(out.results[b]->fracture.params.age) + " age units); a larger --age breaks it further");
    }
  }
  return out;
}

const std::string* body_assignment(const ImportedScene& scene, const SceneBody& body, const SceneAssignments& a) {
  for (int n = body.node; n >= 0; n = scene.nodes[static_cast<std::size_t>(n)].parent) {
    if (auto it = a.by_path.find(scene.nodes[static_cast<std::size_t>(n)].path); it != a.by_path.end()) return &it->second;
  }
  for (int mesh : body.meshes) {
    const int m = scene.meshes[static_cast<std::size_t>(mesh)].material;
    if (m < 0) continue;
    if (auto it = a.by_material.find(scene.materials[static_cast<std::size_t>(m)].name); it != a.by_material.end())
      return &it->second;
  }
  return nullptr;
}

ExportScene scene_export(const ImportedScene& scene, const SceneFracture& fracture) {
  ExportScene out;
  out.up = fracture.up;
  out.frame_name = "scene";
  // Materials: the scene's, a default for meshes with none, and the crack material when a body
  // broke (named so it clashes with none of the scene's).
  std::set<std::string> names;
  for (const SceneMaterial& m : scene.materials) {
    ExportMaterial e;
    e.name = m.name;
    e.colour = m.colour;
    // The base colour's file reference; a texture embedded in the input ("*0") has no file to name.
    if (!m.textures.empty() && m.textures.front().rfind('*', 0) != 0) e.texture = m.textures.front();
    out.materials.push_back(e);
    names.insert(m.name);
  }
  int default_material = -1, crack_material = -1;
  auto unique_name = [&](const std::string& base) {
    std::string name = base;
    for (int k = 1; names.count(name); ++k) name = base + "." + (k < 10 ? "00" : k < 100 ? "0" : "") + std::to_string(k);
    names.insert(name);
    return name;
  };

  // Decided by the scene and the assignments alone, so that every slice lists the same materials.
  bool any_unmaterialled = false, any_assigned = false;
  for (const SceneBody& body : fracture.bodies)
    for (int m : body.meshes) any_unmaterialled = any_unmaterialled || scene.meshes[static_cast<std::size_t>(m)].material < 0;
  for (const SceneBodyReport& r : fracture.reports) any_assigned = any_assigned || r.status != SceneBodyReport::Status::Unassigned;
  if (any_unmaterialled) {
    default_material = static_cast<int>(out.materials.size());
    out.materials.push_back({unique_name("default"), Eigen::Vector3d::Constant(0.8), {}});
  }
  if (any_assigned) {
    crack_material = static_cast<int>(out.materials.size());
    // fragment_scene's crack colour (scene/fragment_export.hpp), under a name no scene material has.
    out.materials.push_back({unique_name("crack"), fragment_scene({}, {}, 1.0).materials.back().colour, {}});
  }
  auto default_index = [&] { return default_material; };
  out.extras_json = scene_slice_extras(fracture.run, fracture.slice, fracture.slices);

  std::vector<int> body_of_node(scene.nodes.size(), -1);
  for (std::size_t b = 0; b < fracture.bodies.size(); ++b)
    body_of_node[static_cast<std::size_t>(fracture.bodies[b].node)] = static_cast<int>(b);

  // The importer's own root above a glTF's scene nodes (assimp's "ROOT": no mesh, no transform).
  const SceneNode& root = scene.nodes.front();
  const bool skip_root = (scene.format == "gltf" || scene.format == "glb") && root.name == "ROOT" && root.meshes.empty() &&
                         root.local.isIdentity(0.0) && scene.nodes.size() > 1;

  std::vector<int> part_of_node(scene.nodes.size(), -1);
  for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
    if (n == 0 && skip_root) continue;
    const SceneNode& node = scene.nodes[n];
    ExportPart part;
    part.name = node.name;
    part.parent = node.parent < 0 ? -1 : part_of_node[static_cast<std::size_t>(node.parent)];
    part.linear = node.local.topLeftCorner<3, 3>();
    part.translation = node.local.topRightCorner<3, 1>();
    const int node_part = static_cast<int>(out.parts.size());
    part_of_node[n] = node_part;
    out.parts.push_back(std::move(part));
    if (body_of_node[n] < 0) continue;

    const std::size_t b = static_cast<std::size_t>(body_of_node[n]);
    const SceneBody& body = fracture.bodies[b];
    const std::optional<FracturedSceneBody>& result = fracture.results[b];
    if (!result) {
      // As read, in the node's frame: its meshes joined, one primitive per material.
      ExportPart& p = out.parts[static_cast<std::size_t>(node_part)];
      Eigen::Index vertices = 0, triangles = 0;
      bool any_uvs = false;
      for (int m : body.meshes) {
        vertices += scene.meshes[static_cast<std::size_t>(m)].vertices.rows();
        triangles += scene.meshes[static_cast<std::size_t>(m)].triangles.rows();
        any_uvs = any_uvs || scene.meshes[static_cast<std::size_t>(m)].uvs.rows() > 0;
      }
      p.vertices.resize(vertices, 3);
      p.triangles.resize(triangles, 3);
      if (any_uvs) p.uvs.setZero(vertices, 2);
      Eigen::Index v0 = 0, t0 = 0;
      for (int m : body.meshes) {
        const SceneMesh& mesh = scene.meshes[static_cast<std::size_t>(m)];
        p.vertices.middleRows(v0, mesh.vertices.rows()) = mesh.vertices;
        if (mesh.uvs.rows() > 0) p.uvs.middleRows(v0, mesh.uvs.rows()) = mesh.uvs;
        p.triangles.middleRows(t0, mesh.triangles.rows()) = mesh.triangles.array() + static_cast<int>(v0);
        p.triangle_material.insert(p.triangle_material.end(), static_cast<std::size_t>(mesh.triangles.rows()),
                                   mesh.material >= 0 ? mesh.material : default_index());
        v0 += mesh.vertices.rows();
        t0 += mesh.triangles.rows();
      }
      continue;
    }
    const BodyFracture& broken = result->fracture;
    const SceneBodyReport& report = fracture.reports[b];
    const nlohmann::ordered_json extras = {{"fissure",
                                            {{"material", report.material_name},
                                             {"seed", report.seed},
                                             {"fragments", broken.fragments.size()},
                                             {"tets", broken.tets}}}};
    out.parts[static_cast<std::size_t>(node_part)].extras_json = extras.dump();
    const ExportScene fragments = fragment_scene(broken.fragments, broken.result.cracks, broken.params.density, result->appearance);
    // fragment_scene's materials are the appearance's, then the crack's.
    std::vector<int> material_map;
    for (int m : result->scene_materials) material_map.push_back(m >= 0 ? m : default_index());
    material_map.push_back(crack_material);
    // World (m) → scene units → the node's frame; fragments keep their origins at their centres
    // of mass. Their extras (volume, mass, centre of mass) stay in SI units.
    Eigen::Matrix4d to_node = body.world.inverse();
    to_node.topLeftCorner<3, 3>() /= fracture.unit;
    const Eigen::Matrix3d linear = to_node.topLeftCorner<3, 3>();
    for (ExportPart f : fragments.parts) {
      f.parent = node_part;
      f.translation = linear * f.translation + to_node.topRightCorner<3, 1>();
      f.vertices = (f.vertices * linear.transpose()).eval();
      for (int& m : f.triangle_material) m = material_map[static_cast<std::size_t>(m)];
      out.parts.push_back(std::move(f));
    }
  }
  return out;
}

}  // namespace fissure
