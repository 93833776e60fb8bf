#include "fissure/io/msh.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "gmsh_session.hpp"

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

// gmsh reads a truncated file without complaint in several cases (it stops at the cut), so the
// section structure is checked here first: a header, a supported version, and both node and
// element sections closed. Binary MSH keeps these markers in ASCII, so the check covers both.
void check_msh_structure(const fs::path& path) {
  const std::string bytes = read_file(path);  // IoError when missing or unreadable
  const std::string name = path.string();
  if (bytes.empty()) throw IoError(name + ": file is empty");
  const std::size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start == std::string::npos || bytes.compare(start, 11, "$MeshFormat") != 0) {
    throw IoError(name + ": not a gmsh MSH file (no $MeshFormat header)");
  }
  const std::size_t version_at = bytes.find_first_not_of(" \t\r\n", start + 11);
  const std::string version = version_at == std::string::npos ? "" : bytes.substr(version_at, 3);
  if (version != "2.2" && version != "4.1" && version != "4.0") {
    throw IoError(name + ": unsupported MSH version '" + version + "' (Fissure reads 2.2 and 4.1)");
  }
  for (const char* section : {"$Nodes", "$EndNodes", "$Elements", "$EndElements"}) {
    if (bytes.find(section) == std::string::npos) {
      throw IoError(name + ": truncated or corrupt MSH file (no " + section + ")");
    }
  }
}

struct Signature {
  std::vector<int> sets;  // indices of the named sets holding an entity
  bool boundary = false;
  bool operator<(const Signature& o) const {
    return boundary != o.boundary ? boundary < o.boundary : sets < o.sets;
  }
};

}  // namespace

TetMesh read_msh(const fs::path& path) {
  check_msh_structure(path);
  const std::string name = path.string();
  GmshSession session;

  std::vector<std::size_t> node_tags, tet_tags, tet_nodes;
  std::vector<double> coords, parametric;
  std::size_t tet10_count = 0;
  std::string error = session.run([&] {
    gmsh::open(name);
    gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
    gmsh::model::mesh::getElementsByType(kTet, tet_tags, tet_nodes);
    std::vector<std::size_t> t10, n10;
    gmsh::model::mesh::getElementsByType(kTet10, t10, n10);
    tet10_count = t10.size();
  });
  if (!error.empty()) throw IoError(name + ": gmsh could not read it: " + error);
  if (tet_tags.empty()) {
    throw InvalidInput(name + (tet10_count ? ": holds only second-order tets (type 11); Fissure needs linear tets"
                                           : ": holds no tetrahedra"));
  }

  // Tets in element-tag order.
  const std::size_t n_tets = tet_tags.size();
  std::vector<std::size_t> order(n_tets);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return tet_tags[a] < tet_tags[b]; });
  std::unordered_map<std::size_t, int> tet_index_of_tag;
  tet_index_of_tag.reserve(n_tets);
  for (std::size_t k = 0; k < n_tets; ++k) tet_index_of_tag[tet_tags[order[k]]] = static_cast<int>(k);

  // Nodes used by tets, renumbered in tag order.
  std::unordered_map<std::size_t, std::size_t> coord_of_tag;
  coord_of_tag.reserve(node_tags.size());
  for (std::size_t i = 0; i < node_tags.size(); ++i) coord_of_tag[node_tags[i]] = i;
  std::vector<std::size_t> used(tet_nodes.begin(), tet_nodes.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::unordered_map<std::size_t, int> index_of_tag;
  index_of_tag.reserve(used.size());
  Eigen::MatrixX3d nodes(static_cast<Eigen::Index>(used.size()), 3);
  for (std::size_t k = 0; k < used.size(); ++k) {
    const auto it = coord_of_tag.find(used[k]);
    if (it == coord_of_tag.end()) {
      throw IoError(name + ": a tet references node tag " + std::to_string(used[k]) + ", which has no coordinates");
    }
    index_of_tag[used[k]] = static_cast<int>(k);
    for (int i = 0; i < 3; ++i) nodes(static_cast<Eigen::Index>(k), i) = coords[3 * it->second + i];
  }
  Eigen::MatrixX4i tets(static_cast<Eigen::Index>(n_tets), 4);
  for (std::size_t k = 0; k < n_tets; ++k)
    for (int a = 0; a < 4; ++a) tets(static_cast<Eigen::Index>(k), a) = index_of_tag[tet_nodes[4 * order[k] + a]];

  // Physical groups → named sets.
  std::vector<NamedSet> sets;
  error = session.run([&] {
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    for (const auto& [dim, tag] : groups) {
      NamedSet set;
      gmsh::model::getPhysicalName(dim, tag, set.name);
      if (set.name.empty()) set.name = "physical_" + std::to_string(dim) + "_" + std::to_string(tag);
      set.dimension = dim;
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
      for (int entity : entities) {
        if (dim == 3) {
          std::vector<std::size_t> et, en;
          gmsh::model::mesh::getElementsByType(kTet, et, en, entity);
          for (std::size_t t : et) set.tets.push_back(tet_index_of_tag.at(t));
          for (std::size_t v : en) set.nodes.push_back(index_of_tag.at(v));
        } else if (dim == 2) {
          std::vector<std::size_t> et, en;
          gmsh::model::mesh::getElementsByType(kTriangle, et, en, entity);
          for (std::size_t f = 0; f + 2 < en.size(); f += 3) {
            const auto a = index_of_tag.find(en[f]), b = index_of_tag.find(en[f + 1]), c = index_of_tag.find(en[f + 2]);
            if (a == index_of_tag.end() || b == index_of_tag.end() || c == index_of_tag.end()) continue;
            set.faces.push_back({a->second, b->second, c->second});
            set.nodes.insert(set.nodes.end(), {a->second, b->second, c->second});
          }
        } else {
          // Point and curve groups: the nodes of their elements (Fissure writes point elements on
          // nodes that belong to the volume) and the nodes classified on the entity.
          std::vector<int> types;
          std::vector<std::vector<std::size_t>> element_tags, element_nodes;
          gmsh::model::mesh::getElements(types, element_tags, element_nodes, dim, entity);
          std::vector<std::size_t> nt;
          std::vector<double> xyz, uvw;
          gmsh::model::mesh::getNodes(nt, xyz, uvw, dim, entity, true, false);
          for (const auto& list : element_nodes) nt.insert(nt.end(), list.begin(), list.end());
          for (std::size_t v : nt) {
            const auto it = index_of_tag.find(v);
            if (it != index_of_tag.end()) set.nodes.push_back(it->second);
          }
        }
      }
      std::sort(set.nodes.begin(), set.nodes.end());
      set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
      std::sort(set.tets.begin(), set.tets.end());
      sets.push_back(std::move(set));
    }
  });
  if (!error.empty()) throw IoError(name + ": gmsh could not read its physical groups: " + error);

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
