#include "fissure/io/msh.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "gmsh_session.hpp"
#include "msh_parser.hpp"

#include <gmsh.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <unordered_map>

namespace fissure {
namespace fs = std::filesystem;
using io_detail::GmshSession;

namespace {

constexpr int kTriangle = 2, kTet = 4, kTet10 = 11, kPoint = 15;


struct Signature {
  std::vector<int> sets;  // indices of the named sets holding an entity
  bool boundary = false;
  bool operator<(const Signature& o) const {
    return boundary != o.boundary ? boundary < o.boundary : sets < o.sets;
  }
};

}  // namespace

TetMesh read_msh(const fs::path& path) {
  const std::string name = path.string();
  const io_detail::MshContent content = io_detail::parse_msh(read_file(path), name);

  // Linear tets in element-tag order. MSH 2.2 writes an element once per physical group it
  // belongs to, so the same tet can appear under several tags: keep the first, merge groups.
  std::vector<const io_detail::MshElement*> tet_elements;
  bool second_order = false;
  for (const auto& e : content.elements) {
    if (e.type == kTet) tet_elements.push_back(&e);
    second_order = second_order || e.type == kTet10;
  }
  if (tet_elements.empty()) {
    throw InvalidInput(name + (second_order ? ": holds only second-order tets (type 11); Fissure needs linear tets"
                                            : ": holds no tetrahedra"));
  }
  std::sort(tet_elements.begin(), tet_elements.end(), [](auto* a, auto* b) { return a->tag < b->tag; });
  std::map<std::array<std::int64_t, 4>, int> tet_of_nodes;
  std::vector<const io_detail::MshElement*> unique_tets;
  for (const auto* e : tet_elements) {
    std::array<std::int64_t, 4> key{e->nodes[0], e->nodes[1], e->nodes[2], e->nodes[3]};
    std::sort(key.begin(), key.end());
    if (tet_of_nodes.emplace(key, static_cast<int>(unique_tets.size())).second) unique_tets.push_back(e);
  }

  // Nodes used by tets, renumbered in tag order.
  std::map<std::int64_t, int> index_of_tag;
  for (const auto* e : unique_tets)
    for (std::int64_t v : e->nodes) index_of_tag.emplace(v, 0);
  int next = 0;
  for (auto& [tag, index] : index_of_tag) index = next++;
  Eigen::MatrixX3d nodes(static_cast<Eigen::Index>(index_of_tag.size()), 3);
  for (const auto& [tag, index] : index_of_tag) {
    const auto& xyz = content.nodes.at(tag);
    nodes.row(index) << xyz[0], xyz[1], xyz[2];
  }
  Eigen::MatrixX4i tets(static_cast<Eigen::Index>(unique_tets.size()), 4);
  for (std::size_t t = 0; t < unique_tets.size(); ++t)
    for (int a = 0; a < 4; ++a) tets(static_cast<Eigen::Index>(t), a) = index_of_tag.at(unique_tets[t]->nodes[static_cast<std::size_t>(a)]);

  // Physical groups → named sets, ordered by (dimension, tag).
  std::map<std::pair<int, int>, NamedSet> groups;
  for (const auto& e : content.elements) {
    for (int physical : e.physicals) {
      NamedSet& set = groups[{e.dimension, physical}];
      bool all_used = true;
      for (std::int64_t v : e.nodes) all_used = all_used && index_of_tag.count(v);
      if (!all_used) continue;  // elements off the tet mesh (e.g. a detached curve)
      for (std::int64_t v : e.nodes) set.nodes.push_back(index_of_tag.at(v));
      if (e.type == kTet) {
        std::array<std::int64_t, 4> key{e.nodes[0], e.nodes[1], e.nodes[2], e.nodes[3]};
        std::sort(key.begin(), key.end());
        set.tets.push_back(tet_of_nodes.at(key));
      } else if (e.type == kTriangle) {
        set.faces.push_back({index_of_tag.at(e.nodes[0]), index_of_tag.at(e.nodes[1]), index_of_tag.at(e.nodes[2])});
      }
    }
  }
  std::vector<NamedSet> sets;
  for (auto& [key, set] : groups) {
    if (set.nodes.empty()) continue;
    const auto named = content.physical_names.find(key);
    set.name = named != content.physical_names.end() ? named->second
                                                     : "physical_" + std::to_string(key.first) + "_" + std::to_string(key.second);
    set.dimension = key.first;
    std::sort(set.nodes.begin(), set.nodes.end());
    set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
    std::sort(set.tets.begin(), set.tets.end());
    set.tets.erase(std::unique(set.tets.begin(), set.tets.end()), set.tets.end());
    sets.push_back(std::move(set));
  }
  return TetMesh(std::move(nodes), std::move(tets), name, std::move(sets));
}

Eigen::MatrixXd voigt_rows_to_tensor_rows(const Eigen::Matrix<double, Eigen::Dynamic, 6>& v) {
  Eigen::MatrixXd out(v.rows(), 9);
  // Voigt (xx, yy, zz, yz, xz, xy) → row-major (xx xy xz; yx yy yz; zx zy zz).
  out.col(0) = v.col(0);
  out.col(1) = v.col(5);
  out.col(2) = v.col(4);
  out.col(3) = v.col(5);
  out.col(4) = v.col(1);
  out.col(5) = v.col(3);
  out.col(6) = v.col(4);
  out.col(7) = v.col(3);
  out.col(8) = v.col(2);
  return out;
}

void write_msh(const fs::path& path, const TetMesh& mesh, const std::vector<MshView>& views,
               const MshWriteOptions& options) {
  const std::string name = path.string();
  for (const MshView& view : views) {
    const Eigen::Index rows = view.kind == MshView::Kind::NodeData ? mesh.node_count() : mesh.tet_count();
    const char* what = view.kind == MshView::Kind::NodeData ? "nodes" : "tets";
    if (view.name.empty()) throw InvalidInput(name + ": a view has no name");
    if (view.values.rows() != rows) {
      throw InvalidInput(name + ": view '" + view.name + "' has " + std::to_string(view.values.rows()) +
                         " rows for " + std::to_string(rows) + " " + what);
    }
    const Eigen::Index c = view.values.cols();
    if (c != 1 && c != 3 && c != 9) {
      throw InvalidInput(name + ": view '" + view.name + "' has " + std::to_string(c) +
                         " components (1, 3 or 9 expected)");
    }
    if (!view.values.allFinite()) throw InvalidInput(name + ": view '" + view.name + "' has non-finite values");
  }

  const int n_nodes = mesh.node_count(), n_tets = mesh.tet_count();
  const auto& sets = mesh.named_sets();

  // Partition tets, faces and loose nodes by the named sets that hold them, so every element is
  // written exactly once and each physical group is a union of whole entities.
  std::vector<Signature> tet_signature(static_cast<std::size_t>(n_tets));
  std::map<std::array<int, 3>, std::pair<std::array<int, 3>, Signature>> faces;  // sorted key → (winding, signature)
  std::map<int, Signature> loose_nodes;
  for (const BoundaryFace& f : mesh.boundary_faces()) {
    auto key = f.nodes;
    std::sort(key.begin(), key.end());
    faces[key] = {f.nodes, Signature{{}, true}};
  }
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const NamedSet& set = sets[s];
    if (set.dimension == 3) {
      for (int t : set.tets) tet_signature[static_cast<std::size_t>(t)].sets.push_back(static_cast<int>(s));
    } else if (set.dimension == 2 && !set.faces.empty()) {
      for (const auto& face : set.faces) {
        auto key = face;
        std::sort(key.begin(), key.end());
        auto [it, inserted] = faces.try_emplace(key, face, Signature{});
        it->second.second.sets.push_back(static_cast<int>(s));
      }
    } else {
      for (int v : set.nodes) loose_nodes[v].sets.push_back(static_cast<int>(s));
    }
  }

  GmshSession session;
  const std::string error = session.run([&] {
    gmsh::model::add("fissure");
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", options.binary ? 1 : 0);
    gmsh::option::setNumber("Mesh.SaveAll", 1);  // keep every element even when groups exist
    gmsh::option::setNumber("PostProcessing.SaveMesh", 0);

    std::map<int, std::vector<int>> group_entities[4];  // per dim: set index → entity tags

    // Volume entities, one per tet signature, in order of first appearance.
    std::map<Signature, int> volume_of;
    std::vector<std::vector<std::size_t>> volume_tets;
    for (int t = 0; t < n_tets; ++t) {
      const auto [it, inserted] = volume_of.try_emplace(tet_signature[static_cast<std::size_t>(t)],
                                                        static_cast<int>(volume_tets.size()) + 1);
      if (inserted) volume_tets.emplace_back();
      volume_tets[static_cast<std::size_t>(it->second - 1)].push_back(static_cast<std::size_t>(t));
    }
    for (std::size_t e = 0; e < volume_tets.size(); ++e) gmsh::model::addDiscreteEntity(3, static_cast<int>(e) + 1);
    std::vector<std::size_t> node_tags(static_cast<std::size_t>(n_nodes));
    std::vector<double> coords(3 * static_cast<std::size_t>(n_nodes));
    for (int v = 0; v < n_nodes; ++v) {
      node_tags[static_cast<std::size_t>(v)] = static_cast<std::size_t>(v) + 1;
      for (int i = 0; i < 3; ++i) coords[3 * static_cast<std::size_t>(v) + i] = mesh.nodes()(v, i);
    }
    gmsh::model::mesh::addNodes(3, 1, node_tags, coords);
    for (std::size_t e = 0; e < volume_tets.size(); ++e) {
      std::vector<std::size_t> tags, conn;
      for (std::size_t t : volume_tets[e]) {
        tags.push_back(t + 1);  // element tag = tet index + 1: reading back keeps the order
        for (int a = 0; a < 4; ++a) conn.push_back(static_cast<std::size_t>(mesh.tets()(static_cast<Eigen::Index>(t), a)) + 1);
      }
      gmsh::model::mesh::addElementsByType(static_cast<int>(e) + 1, kTet, tags, conn);
    }
    for (const auto& [signature, entity] : volume_of)
      for (int s : signature.sets) group_entities[3][s].push_back(entity);

    // Surface entities: boundary triangles and set faces, one entity per signature.
    std::map<Signature, std::vector<std::array<int, 3>>> surface_faces;
    std::vector<Signature> surface_order;
    for (const auto& [key, value] : faces) {
      auto [it, inserted] = surface_faces.try_emplace(value.second);
      if (inserted) surface_order.push_back(value.second);
      it->second.push_back(value.first);
    }
    std::size_t next_tag = static_cast<std::size_t>(n_tets) + 1;
    int surface_tag = 0;
    for (const Signature& signature : surface_order) {
      ++surface_tag;
      gmsh::model::addDiscreteEntity(2, surface_tag);
      std::vector<std::size_t> tags, conn;
      for (const auto& face : surface_faces[signature]) {
        tags.push_back(next_tag++);
        for (int v : face) conn.push_back(static_cast<std::size_t>(v) + 1);
      }
      gmsh::model::mesh::addElementsByType(surface_tag, kTriangle, tags, conn);
      for (int s : signature.sets) group_entities[2][s].push_back(surface_tag);
    }

    // Loose node sets (dimension 0 or 1): point elements on point entities, one per signature.
    std::map<Signature, std::vector<int>> point_nodes;
    std::vector<Signature> point_order;
    for (const auto& [v, signature] : loose_nodes) {
      auto [it, inserted] = point_nodes.try_emplace(signature);
      if (inserted) point_order.push_back(signature);
      it->second.push_back(v);
    }
    int point_tag = 0;
    for (const Signature& signature : point_order) {
      ++point_tag;
      gmsh::model::addDiscreteEntity(0, point_tag);
      std::vector<std::size_t> tags, conn;
      for (int v : point_nodes[signature]) {
        tags.push_back(next_tag++);
        conn.push_back(static_cast<std::size_t>(v) + 1);
      }
      gmsh::model::mesh::addElementsByType(point_tag, kPoint, tags, conn);
      for (int s : signature.sets) group_entities[0][s].push_back(point_tag);
    }

    for (std::size_t s = 0; s < sets.size(); ++s) {
      const int dim = sets[s].dimension == 3 ? 3 : (sets[s].dimension == 2 && !sets[s].faces.empty() ? 2 : 0);
      const auto it = group_entities[dim].find(static_cast<int>(s));
      if (it == group_entities[dim].end()) continue;  // an empty set has nothing to carry it
      const int group = gmsh::model::addPhysicalGroup(dim, it->second, static_cast<int>(s) + 1);
      gmsh::model::setPhysicalName(dim, group, sets[s].name);
    }
  });
  if (!error.empty()) throw IoError(name + ": gmsh could not build the mesh: " + error);

  write_atomically(path, [&](const fs::path& temp) {
    const std::string failure = session.run([&] {
      gmsh::write(temp.string());
      std::string model;
      gmsh::model::getCurrent(model);
      for (const MshView& view : views) {
        const bool nodal = view.kind == MshView::Kind::NodeData;
        const Eigen::Index rows = view.values.rows(), cols = view.values.cols();
        std::vector<std::size_t> tags(static_cast<std::size_t>(rows));
        std::vector<double> data(static_cast<std::size_t>(rows * cols));
        for (Eigen::Index r = 0; r < rows; ++r) {
          tags[static_cast<std::size_t>(r)] = static_cast<std::size_t>(r) + 1;  // node or tet tag
          for (Eigen::Index c = 0; c < cols; ++c) data[static_cast<std::size_t>(r * cols + c)] = view.values(r, c);
        }
        const int tag = gmsh::view::add(view.name);
        gmsh::view::addHomogeneousModelData(tag, 0, model, nodal ? "NodeData" : "ElementData", tags, data, 0.0,
                                            static_cast<int>(cols));
        gmsh::view::write(tag, temp.string(), true);
        gmsh::view::remove(tag);
      }
    });
    if (!failure.empty()) throw IoError(name + ": gmsh could not write it: " + failure);
  });
}

}  // namespace fissure
