#include "fissure/io/msh.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "msh_parser.hpp"
#include "msh_writer.hpp"

#include <algorithm>
#include <cctype>
#include <map>

namespace fissure {
namespace fs = std::filesystem;

namespace {

constexpr int kTriangle = 2, kTet = 4, kTet10 = 11;

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
  // The file's tags name nodes and tets in every later message, as gmsh shows them.
  EntityTags tags;
  Eigen::MatrixX3d nodes(static_cast<Eigen::Index>(index_of_tag.size()), 3);
  for (const auto& [tag, index] : index_of_tag) {
    const auto& xyz = content.nodes.at(tag);
    nodes.row(index) << xyz[0], xyz[1], xyz[2];
    tags.nodes.push_back(tag);
  }
  Eigen::MatrixX4i tets(static_cast<Eigen::Index>(unique_tets.size()), 4);
  for (std::size_t t = 0; t < unique_tets.size(); ++t) {
    for (int a = 0; a < 4; ++a) tets(static_cast<Eigen::Index>(t), a) = index_of_tag.at(unique_tets[t]->nodes[static_cast<std::size_t>(a)]);
    tags.tets.push_back(unique_tets[t]->tag);
  }

  // Physical groups → named sets, ordered by (tag, dimension): Fissure writes set i as group
  // i + 1, so a mesh read back keeps its sets' order and is written again byte for byte.
  std::map<std::pair<int, int>, NamedSet> groups;
  for (const auto& e : content.elements) {
    for (int physical : e.physicals) {
      NamedSet& set = groups[{physical, e.dimension}];
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
    const auto [tag, dim] = key;
    const auto named = content.physical_names.find({dim, tag});
    set.name = named != content.physical_names.end() ? named->second
                                                     : "physical_" + std::to_string(dim) + "_" + std::to_string(tag);
    set.dimension = dim;
    std::sort(set.nodes.begin(), set.nodes.end());
    set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
    std::sort(set.tets.begin(), set.tets.end());
    set.tets.erase(std::unique(set.tets.begin(), set.tets.end()), set.tets.end());
    sets.push_back(std::move(set));
  }
  return TetMesh(std::move(nodes), std::move(tets), name, std::move(sets), std::move(tags));
}

void check_msh_output_path(const fs::path& path) {
  if (!is_stream_target(path)) {
    std::string file = path.filename().string();
    std::transform(file.begin(), file.end(), file.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    // Before the checks of the path itself: `-o x.stl` must not be written as MSH under that name.
    if (file.size() < 4 || file.compare(file.size() - 4, 4, ".msh") != 0) {
      throw IoError(path.string() + ": the output must end in .msh");
    }
  }
  check_output_path(path);
}

void write_msh(const fs::path& path, const TetMesh& mesh, const std::vector<MshView>& views,
               const MshWriteOptions& options, const std::vector<NamedSet>& extra_sets) {
  check_msh_output_path(path);
  write_file_atomically(path, io_detail::encode_msh41(mesh, views, options.binary, extra_sets, path.string()));
}

}  // namespace fissure
