#include "msh_writer.hpp"

#include "fissure/base/error.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <string_view>
#include <unordered_set>

namespace fissure::io_detail {
namespace {

constexpr int kPoint = 15, kTriangle = 2, kTet = 4;
// Our reader (and gmsh's int-based views) take tags up to 2³¹ − 1.
constexpr std::int64_t kMaxTag = std::numeric_limits<std::int32_t>::max();

// Appends MSH fields. ASCII: decimal text separated by spaces, one row per line, doubles in the
// shortest form that reads back to the same value (std::to_chars), so ASCII round-trips bit for
// bit. Binary: the raw little-endian bytes of the type the manual gives each field (int →
// int32, size_t → uint64, double), no separators.
class Fields {
public:
  Fields(std::string& out, bool binary) : m_out(out), m_binary(binary) {}
  void size(std::uint64_t v) { m_binary ? raw(v) : text(v); }
  void integer(std::int32_t v) { m_binary ? raw(v) : text(v); }
  void real(double v) { m_binary ? raw(v) : text(v); }
  void end_row() {
    if (!m_binary && !m_out.empty() && m_out.back() == ' ') m_out.back() = '\n';
  }
  /// A line of text in either mode: section markers and the headers of views.
  void line(std::string_view s) {
    m_out.append(s);
    m_out.push_back('\n');
  }
  /// Binary data is followed by a newline before its $End marker, as gmsh writes it.
  void end_binary() {
    if (m_binary) m_out.push_back('\n');
  }

private:
  template <class T>
  void raw(T v) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    m_out.append(bytes, sizeof(T));
  }
  template <class T>
  void text(T v) {
    char digits[32];  // the longest shortest double, "-2.2250738585072014e-308", has 24 characters
    const auto end = std::to_chars(digits, digits + sizeof digits, v).ptr;
    m_out.append(digits, end);
    m_out.push_back(' ');
  }
  std::string& m_out;
  bool m_binary;
};

// The named sets that hold a tet, a face or a loose node, and whether a face is on the boundary:
// elements with the same signature share one entity, so each physical group is a union of whole
// entities and every element is written exactly once.
struct Signature {
  std::vector<int> sets;  // ascending set indices
  bool boundary = false;
  bool operator<(const Signature& o) const { return boundary != o.boundary ? boundary < o.boundary : sets < o.sets; }
};

// One elementary entity and its elements (all of one type).
struct Entity {
  std::vector<int> physicals;        // physical tags: set index + 1
  std::vector<std::int64_t> tags;    // element tags
  std::vector<int> connectivity;     // node indices, nodes-per-element per element
  std::array<double, 6> box{};       // min xyz, max xyz of the element nodes
};

struct Model {
  std::array<std::vector<Entity>, 4> entities;  // by dimension (1 stays empty)
  std::vector<std::pair<std::pair<int, int>, std::string>> physical_names;  // ((dim, tag), name), sorted
};

void bound(Entity& entity, const TetMesh& mesh) {
  if (entity.connectivity.empty()) return;
  Eigen::Array3d lo = mesh.nodes().row(entity.connectivity[0]).transpose(), hi = lo;
  for (int v : entity.connectivity) {
    lo = lo.min(mesh.nodes().row(v).transpose().array());
    hi = hi.max(mesh.nodes().row(v).transpose().array());
  }
  entity.box = {lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()};
}

std::vector<int> physical_tags(const Signature& s) {
  std::vector<int> tags;
  for (int set : s.sets) tags.push_back(set + 1);
  return tags;
}

// Partitions tets, faces and loose nodes into entities by signature, in order of first
// appearance; tets keep their tags, the other elements are numbered after the largest tet tag.
Model build_model(const TetMesh& mesh, const std::vector<NamedSet>& sets, const std::string& name) {
  const int n_tets = mesh.tet_count();
  std::vector<Signature> tet_signature(static_cast<std::size_t>(n_tets));
  std::map<std::array<int, 3>, std::pair<std::array<int, 3>, Signature>> faces;  // sorted key → (winding, signature)
  std::map<int, Signature> loose_nodes;
  for (const BoundaryFace& f : mesh.boundary_faces()) {
    auto key = f.nodes;
    std::sort(key.begin(), key.end());
    faces[key] = {f.nodes, Signature{{}, true}};
  }
  std::vector<int> group_dimension(sets.size());
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const NamedSet& set = sets[s];
    const int index = static_cast<int>(s);
    auto join = [index](Signature& signature) {  // once, even when the set lists an item twice
      if (signature.sets.empty() || signature.sets.back() != index) signature.sets.push_back(index);
    };
    if (set.dimension == 3) {
      group_dimension[s] = 3;
      for (int t : set.tets) join(tet_signature[static_cast<std::size_t>(t)]);
    } else if (set.dimension == 2 && !set.faces.empty()) {
      group_dimension[s] = 2;
      for (const auto& face : set.faces) {
        auto key = face;
        std::sort(key.begin(), key.end());
        join(faces.try_emplace(key, face, Signature{}).first->second.second);
      }
    } else {
      group_dimension[s] = 0;  // node sets (and curves) become point elements
      for (int v : set.nodes) join(loose_nodes[v]);
    }
  }

  Model model;
  std::vector<bool> has_group(sets.size(), false);
  auto entity_for = [&](int dim, std::map<Signature, std::size_t>& index, const Signature& signature) -> Entity& {
    auto& list = model.entities[static_cast<std::size_t>(dim)];
    const auto [it, inserted] = index.try_emplace(signature, list.size());
    if (inserted) {
      list.emplace_back();
      list.back().physicals = physical_tags(signature);
      for (int s : signature.sets) has_group[static_cast<std::size_t>(s)] = true;
    }
    return list[it->second];
  };

  std::int64_t max_tet_tag = 0;
  std::map<Signature, std::size_t> volume_of, surface_of, point_of;
  for (int t = 0; t < n_tets; ++t) {
    Entity& e = entity_for(3, volume_of, tet_signature[static_cast<std::size_t>(t)]);
    e.tags.push_back(mesh.tet_tag(t));
    max_tet_tag = std::max(max_tet_tag, mesh.tet_tag(t));
    for (int a = 0; a < 4; ++a) e.connectivity.push_back(mesh.tets()(t, a));
  }
  std::int64_t next_tag = max_tet_tag + 1;
  for (const auto& [key, value] : faces) {
    Entity& e = entity_for(2, surface_of, value.second);
    e.connectivity.insert(e.connectivity.end(), value.first.begin(), value.first.end());
  }
  for (const auto& [v, signature] : loose_nodes) entity_for(0, point_of, signature).connectivity.push_back(v);
  // Numbered surface by surface, then point by point: each entity's elements are consecutive.
  for (int dim : {2, 0}) {
    const std::size_t per = dim == 2 ? 3 : 1;
    for (Entity& e : model.entities[static_cast<std::size_t>(dim)]) {
      for (std::size_t i = 0; i < e.connectivity.size() / per; ++i) e.tags.push_back(next_tag++);
    }
  }
  if (next_tag - 1 > kMaxTag) {
    throw InvalidInput(name + ": the boundary triangles and set nodes would be numbered up to " + std::to_string(next_tag - 1) +
                       ", past the largest MSH tag " + std::to_string(kMaxTag) + " (the largest tet tag is " +
                       std::to_string(max_tet_tag) + ")");
  }
  for (auto& list : model.entities)
    for (Entity& e : list) bound(e, mesh);

  for (std::size_t s = 0; s < sets.size(); ++s) {
    if (has_group[s]) model.physical_names.push_back({{group_dimension[s], static_cast<int>(s) + 1}, sets[s].name});
  }
  std::sort(model.physical_names.begin(), model.physical_names.end());
  return model;
}

void write_entities(Fields& f, const Model& model) {
  f.line("$Entities");
  for (const auto& list : model.entities) f.size(list.size());
  f.end_row();
  for (int dim = 0; dim < 4; ++dim) {
    const auto& list = model.entities[static_cast<std::size_t>(dim)];
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Entity& e = list[i];
      f.integer(static_cast<std::int32_t>(i) + 1);
      // A point entity has a position (the low corner of its nodes); the others a bounding box.
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) f.real(e.box[static_cast<std::size_t>(k)]);
      f.size(e.physicals.size());
      for (int p : e.physicals) f.integer(p);
      if (dim > 0) f.size(0);  // no bounding entities: the mesh is discrete
      f.end_row();
    }
  }
  f.end_binary();
  f.line("$EndEntities");
}

// Every node in one block on volume entity 1 (the entity of the first tet); elements of every
// entity refer to them by tag, which gmsh and Fissure's reader both accept.
void write_nodes(Fields& f, const TetMesh& mesh) {
  f.line("$Nodes");
  const int n = mesh.node_count();
  std::int64_t lo = 0, hi = 0;
  for (int v = 0; v < n; ++v) {
    lo = v == 0 ? mesh.node_tag(v) : std::min(lo, mesh.node_tag(v));
    hi = std::max(hi, mesh.node_tag(v));
  }
  f.size(n > 0 ? 1 : 0);
  f.size(static_cast<std::uint64_t>(n));
  f.size(static_cast<std::uint64_t>(lo));
  f.size(static_cast<std::uint64_t>(hi));
  f.end_row();
  if (n > 0) {
    f.integer(3);
    f.integer(1);
    f.integer(0);  // no parametric coordinates
    f.size(static_cast<std::uint64_t>(n));
    f.end_row();
    for (int v = 0; v < n; ++v) {
      f.size(static_cast<std::uint64_t>(mesh.node_tag(v)));
      f.end_row();
    }
    for (int v = 0; v < n; ++v) {
      for (int k = 0; k < 3; ++k) f.real(mesh.nodes()(v, k));
      f.end_row();
    }
  }
  f.end_binary();
  f.line("$EndNodes");
}

void write_elements(Fields& f, const TetMesh& mesh, const Model& model) {
  f.line("$Elements");
  std::size_t blocks = 0, total = 0;
  std::int64_t lo = 0, hi = 0;
  for (const auto& list : model.entities) {
    for (const Entity& e : list) {
      ++blocks;
      total += e.tags.size();
      for (std::int64_t tag : e.tags) {
        lo = lo == 0 ? tag : std::min(lo, tag);
        hi = std::max(hi, tag);
      }
    }
  }
  f.size(blocks);
  f.size(total);
  f.size(static_cast<std::uint64_t>(lo));
  f.size(static_cast<std::uint64_t>(hi));
  f.end_row();
  for (int dim = 0; dim < 4; ++dim) {
    const int type = dim == 3 ? kTet : dim == 2 ? kTriangle : kPoint;
    const std::size_t per = dim == 3 ? 4 : dim == 2 ? 3 : 1;
    const auto& list = model.entities[static_cast<std::size_t>(dim)];
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Entity& e = list[i];
      f.integer(dim);
      f.integer(static_cast<std::int32_t>(i) + 1);
      f.integer(type);
      f.size(e.tags.size());
      f.end_row();
      for (std::size_t k = 0; k < e.tags.size(); ++k) {
        f.size(static_cast<std::uint64_t>(e.tags[k]));
        for (std::size_t a = 0; a < per; ++a) f.size(static_cast<std::uint64_t>(mesh.node_tag(e.connectivity[k * per + a])));
        f.end_row();
      }
    }
  }
  f.end_binary();
  f.line("$EndElements");
}

// Model-based data (gmsh manual §10.1, $NodeData / $ElementData): one string tag (the name),
// one real tag (time 0), three integer tags (time step 0, components, rows). The header is text
// in both modes; in binary each row is an int32 tag followed by its doubles.
void write_view(Fields& f, const TetMesh& mesh, const MshView& view) {
  const bool nodal = view.kind == MshView::Kind::NodeData;
  const Eigen::Index rows = view.values.rows(), cols = view.values.cols();
  f.line(nodal ? "$NodeData" : "$ElementData");
  f.line("1");
  f.line("\"" + view.name + "\"");
  f.line("1");
  f.line("0");
  f.line("3");
  f.line("0");
  f.line(std::to_string(cols));
  f.line(std::to_string(rows));
  for (Eigen::Index r = 0; r < rows; ++r) {
    const std::int64_t tag = nodal ? mesh.node_tag(static_cast<int>(r)) : mesh.tet_tag(static_cast<int>(r));
    f.integer(static_cast<std::int32_t>(tag));
    for (Eigen::Index c = 0; c < cols; ++c) f.real(view.values(r, c));
    f.end_row();
  }
  f.end_binary();
  f.line(nodal ? "$EndNodeData" : "$EndElementData");
}

// A name goes between double quotes on one line of the file: gmsh reads up to the next quote.
void check_name(const std::string& text, const std::string& what, const std::string& name) {
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || u < 0x20 || u == 0x7f) {
      throw InvalidInput(name + ": " + what + " holds a double quote or a control character, which MSH cannot store");
    }
  }
}

void check_tags(const std::vector<std::int64_t>& tags, const char* what, const std::string& name) {
  std::unordered_set<std::int64_t> seen;
  seen.reserve(tags.size());
  for (std::int64_t tag : tags) {
    if (tag < 1 || tag > kMaxTag) {
      throw InvalidInput(name + ": " + what + " tag " + std::to_string(tag) + " is outside [1, " + std::to_string(kMaxTag) + "]");
    }
    if (!seen.insert(tag).second) throw InvalidInput(name + ": " + what + " tag " + std::to_string(tag) + " is used twice");
  }
}

void check_inputs(const TetMesh& mesh, const std::vector<MshView>& views, const std::vector<NamedSet>& sets,
                  const std::string& name) {
  for (const MshView& view : views) {
    const bool nodal = view.kind == MshView::Kind::NodeData;
    const Eigen::Index rows = nodal ? mesh.node_count() : mesh.tet_count();
    if (view.name.empty()) throw InvalidInput(name + ": a view has no name");
    check_name(view.name, "view '" + view.name + "'", name);
    if (view.values.rows() != rows) {
      throw InvalidInput(name + ": view '" + view.name + "' has " + std::to_string(view.values.rows()) + " rows for " +
                         std::to_string(rows) + (nodal ? " nodes" : " tets"));
    }
    const Eigen::Index c = view.values.cols();
    if (c != 1 && c != 3 && c != 9) {
      throw InvalidInput(name + ": view '" + view.name + "' has " + std::to_string(c) + " components (1, 3 or 9 expected)");
    }
    for (Eigen::Index r = 0; r < view.values.rows(); ++r) {
      if (!view.values.row(r).allFinite()) {
        throw InvalidInput(name + ": view '" + view.name + "' has a non-finite value at " +
                           (nodal ? mesh.node_label(static_cast<int>(r)) : mesh.tet_label(static_cast<int>(r))));
      }
    }
  }
  for (const NamedSet& set : sets) {
    check_name(set.name, "set '" + set.name + "'", name);
    const auto check_index = [&](int i, int count, const char* what) {
      if (i < 0 || i >= count)
        throw InvalidInput(name + ": set '" + set.name + "' " + what + " " + std::to_string(i) + " of " +
                           std::to_string(count));
    };
    for (int t : set.tets) check_index(t, mesh.tet_count(), "lists tet");
    for (int v : set.nodes) check_index(v, mesh.node_count(), "lists node");
    for (const auto& face : set.faces)
      for (int v : face) check_index(v, mesh.node_count(), "has a face on node");
  }
  check_tags(mesh.tags().nodes, "node", name);
  check_tags(mesh.tags().tets, "tet", name);
}

}  // namespace

std::string encode_msh41(const TetMesh& mesh, const std::vector<MshView>& views, bool binary,
                         const std::vector<NamedSet>& extra_sets, const std::string& name) {
  std::vector<NamedSet> sets = mesh.named_sets();
  sets.insert(sets.end(), extra_sets.begin(), extra_sets.end());
  check_inputs(mesh, views, sets, name);
  const Model model = build_model(mesh, sets, name);

  std::string out;
  // About 100 bytes per node and 60 per element in ASCII, 24 + 8 per value in views.
  std::size_t estimate = 4096 + 100 * static_cast<std::size_t>(mesh.node_count()) + 60 * static_cast<std::size_t>(mesh.tet_count()) +
                         60 * mesh.boundary_faces().size();
  for (const MshView& view : views) estimate += static_cast<std::size_t>(view.values.rows()) * (12 + 25 * static_cast<std::size_t>(view.values.cols()));
  out.reserve(estimate);
  Fields f(out, binary);

  f.line("$MeshFormat");
  f.line(binary ? "4.1 1 8" : "4.1 0 8");
  if (binary) {
    f.integer(1);  // lets a reader detect the byte order
    f.end_binary();
  }
  f.line("$EndMeshFormat");
  if (!model.physical_names.empty()) {
    f.line("$PhysicalNames");
    f.line(std::to_string(model.physical_names.size()));
    for (const auto& [key, text] : model.physical_names) {
      f.line(std::to_string(key.first) + " " + std::to_string(key.second) + " \"" + text + "\"");
    }
    f.line("$EndPhysicalNames");
  }
  write_entities(f, model);
  write_nodes(f, mesh);
  write_elements(f, mesh, model);
  for (const MshView& view : views) write_view(f, mesh, view);
  return out;
}

}  // namespace fissure::io_detail
