#pragma once
// Private to io: the bytes of a MSH 4.1 file, ASCII or binary, built in memory.
//
// Fissure writes MSH itself instead of through the gmsh API: gmsh's writer does not report
// failed writes (a full disk left a truncated file and exit 0), links ~53 shared libraries into
// every command, and its ASCII writer took 144 ms at 24K tets with views. The layout follows the
// gmsh manual's MSH 4.1 description (§10.1); the tests read every file with gmsh itself.

#include "fissure/io/msh.hpp"
#include "fissure/mesh/tet_mesh.hpp"

#include <string>
#include <vector>

namespace fissure::io_detail {

/// The whole file: $MeshFormat, $PhysicalNames, $Entities, $Nodes, $Elements, then one
/// $NodeData / $ElementData per view. Throws InvalidInput prefixed by `name` for what write_msh
/// documents (view shapes, non-finite values, names, tags). Same inputs, same bytes.
std::string encode_msh41(const TetMesh& mesh, const std::vector<MshView>& views, bool binary,
                         const std::vector<NamedSet>& extra_sets, const std::string& name);

}  // namespace fissure::io_detail
