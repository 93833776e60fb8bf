#pragma once
/// gmsh MSH files, through the gmsh API: read 2.2 and 4.1 (ASCII or binary), write 4.1 with
/// physical groups and post-processing views that gmsh displays.

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
/// node-tag order; tets keep element-tag order. The mesh's source_name is the path, so mesh errors
/// read "file.msh: tet 97 is inverted".
/// Throws IoError naming the file when it is missing, empty, truncated, corrupt or not MSH, and
/// InvalidInput when it holds no linear tets (or only second-order ones). Thread-safe.
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

/// Writes MSH 4.1 through the gmsh API: the tets in volume entities, the boundary triangles and
/// the named sets as physical groups (so a round trip keeps them), then each view as model-based
/// post-processing data. Atomic: the file appears complete or not at all. Throws InvalidInput
/// naming a view with the wrong row count, component count or a non-finite value, IoError when
/// the file cannot be written. Same mesh and views → same bytes.
void write_msh(const std::filesystem::path& path, const TetMesh& mesh,
               const std::vector<MshView>& views = {}, const MshWriteOptions& options = {});

/// Row-major 3×3 tensors (9 columns) from Voigt stresses (xx, yy, zz, yz, xz, xy), for views.
Eigen::MatrixXd voigt_rows_to_tensor_rows(const Eigen::Matrix<double, Eigen::Dynamic, 6>& voigt);

}  // namespace fissure
