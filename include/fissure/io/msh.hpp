#pragma once
/// gmsh MSH files, with Fissure's own code (no gmsh library at run time): read 2.2 and 4.1
/// (ASCII or binary), write 4.1 with physical groups and post-processing views that gmsh
/// displays. The tests open every file written here with gmsh itself.

#include "fissure/mesh/tet_mesh.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace fissure {

/// Reads the linear tetrahedra (gmsh element type 4) of a MSH 2.2 or 4.1 file with Fissure's own
/// strict parser (gmsh's reader crashes on some corrupt files; see src/io/msh_parser.hpp). Physical groups
/// become NamedSets: name (or "physical_<dim>_<tag>" when unnamed), dimension, nodes, triangles
/// of 2-D groups, tets of 3-D groups. Nodes used by no tet are dropped and the rest renumbered in
/// node-tag order; tets keep element-tag order. The file's node and element tags become the
/// mesh's EntityTags and its source_name is the path, so mesh errors read
/// "file.msh: tet 1203 is inverted" with the numbers gmsh shows.
/// Throws IoError naming the file and the culprit (section and byte, node or element tag) when
/// it is missing, empty, truncated, corrupt or not MSH, and InvalidInput when it holds no linear
/// tets (or only second-order ones) or its tets do not form a valid TetMesh. Thread-safe.
/// O(file size · log).
TetMesh read_msh(const std::filesystem::path& path);

/// Post-processing data written beside the mesh: one row per node (NodeData) or per tet
/// (ElementData), 1 column for a scalar, 3 for a vector, 9 for a tensor (row-major xx xy xz yx …).
struct MshView {
  enum class Kind { NodeData, ElementData };
  std::string name;
  Kind kind = Kind::NodeData;
  Eigen::MatrixXd values;
};

struct MshWriteOptions {
  bool binary = false;  ///< binary MSH 4.1 (smaller, faster) instead of ASCII
};

/// Throws IoError "<path>: the output must end in .msh" unless `path` ends in ".msh" (any case)
/// or is a stream target ("-", a FIFO, a character device: see is_stream_target), and IoError
/// from check_output_path when it cannot be written. Commands call it before any long work.
void check_msh_output_path(const std::filesystem::path& path);

/// Writes MSH 4.1: the nodes, the tets in volume entities, the boundary triangles and the named
/// sets as named physical groups (so a round trip keeps them), then each view as model-based
/// NodeData / ElementData. Nodes and elements carry the mesh's tags (TetMesh::node_tag /
/// tet_tag; triangles and points are numbered after the largest tet tag), so a mesh read from a
/// file is written with the numbers its user knows. ASCII numbers are the shortest text that
/// reads back to the same double, so both formats round-trip bit for bit.
/// The whole file is built in memory and committed with write_file_atomically: every write is
/// checked, and a failed write (full disk, file size limit) leaves the previous file intact.
/// `extra_sets` are written after the mesh's own named sets and checked like them (fracture
/// writes each fragment's tets as a 3-D group "fragment_NNN"). Same inputs → same bytes.
/// Throws IoError naming the path when it does not end in .msh (see check_msh_output_path) or
/// cannot be written; InvalidInput naming the view or set
/// for a view with the wrong row count, component count or a non-finite value, a name holding
/// a double quote or a control character, or tags that are not unique positive 31-bit integers.
/// O(#tets log #tets); holds the whole file in memory (about 100 bytes per tet, plus up to 25
/// per view value in ASCII).
void write_msh(const std::filesystem::path& path, const TetMesh& mesh,
               const std::vector<MshView>& views = {}, const MshWriteOptions& options = {},
               const std::vector<NamedSet>& extra_sets = {});

}  // namespace fissure
