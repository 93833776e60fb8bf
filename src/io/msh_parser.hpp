#pragma once
// Private to io: a strict reader of the gmsh MSH formats 2.2 and 4.1, ASCII and binary.
//
// Fissure parses MSH itself instead of calling gmsh's reader because gmsh 4.8.4 crashes on
// corrupt input (measured: ~2 % of randomly corrupted 4.1 files segfault or hang, e.g. on node
// tags ≥ 2³¹ or a negative physical dimension) and runs anything that does not start with
// $MeshFormat as a .geo script (`Exit;`, `SystemCall`). This reader checks every count against
// the bytes that remain, every tag's range and every element's nodes, and throws IoError naming
// the file and the section (node and element tags as the file gives them). msh_writer.hpp
// writes; the tests read gmsh's own files here and open ours with gmsh.

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace fissure::io_detail {

struct MshElement {
  std::int64_t tag = 0;
  int type = 0;            // gmsh element type (4 = linear tet, 2 = triangle, 15 = point, …)
  int dimension = 0;       // of the element type
  int entity = 0;          // elementary entity tag
  std::vector<int> physicals;  // MSH 2.2: the element's physical tag; 4.1: from its entity
  std::vector<std::int64_t> nodes;
};

struct MshContent {
  double version = 0.0;
  bool binary = false;
  std::map<std::int64_t, std::array<double, 3>> nodes;  // by node tag
  std::vector<MshElement> elements;
  std::map<std::pair<int, int>, std::string> physical_names;  // (dimension, tag) → name
};

/// Parses `bytes` (the whole file). `name` prefixes every error.
MshContent parse_msh(const std::string& bytes, const std::string& name);

/// Nodes of a gmsh element type, or −1 for a type this reader does not know.
int msh_nodes_per_element(int type);
/// Dimension of a gmsh element type, or −1.
int msh_element_dimension(int type);

}  // namespace fissure::io_detail
