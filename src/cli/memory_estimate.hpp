#pragma once
// Peak memory of the CLI's big requests, estimated before any work so that a request far
// beyond the machine (mesh --tets 5e7, modes --count 5000 on a large mesh) is refused at once
// with the estimate, unless --allow-large is given.
//
// The coefficients are peak RSS measurements of this CLI (GNU time -v, Release build, the
// tile:1,1,0.05 plate); the estimates are linear fits through them, within 3 % at every measured
// point. Sparse factors fill in faster than linearly in 3-D, so far beyond the measured sizes the
// estimates are low: the safe side for a refusal, which must never hit a request that fits.

#include <cstdint>

namespace fissure::cli {

/// `fissure mesh` for `tets` tetrahedra, bytes. Measured: 110.7 MB at 21 486 tets, 230.9 MB at
/// 197 378 tets: 0.684 kB a tet on top of 96 MB.
double meshing_bytes(double tets);

/// A modal basis of `modes` flexible modes (plus 6 rigid ones for a free body) of a mesh with
/// `tets` tets and `nodes` nodes, bytes. Measured with `fissure modes --no-cache`: at 21 486 tets
/// (16 677 dofs) 167.0 MB for 10 modes, 297.3 MB for 200, 427.4 MB for 400: 40 bytes a dof and
/// mode (the Lanczos basis of 2m + 1 vectors, the eigenvectors and the expanded modes); 1067 MB
/// for 10 modes at 197 378 tets (118 635 dofs): 4.8 kB a tet (K, M and the shift-invert factor)
/// on top of 50 MB.
double modal_bytes(double tets, double nodes, double modes);

/// A direct static solve, bytes. Measured with `fissure solve`: 162.9 MB at 21 486 tets, 943.0 MB
/// at 197 378 tets: 4.44 kB a tet on top of 68 MB.
double static_solve_bytes(double tets);

/// The limit passed to require_memory: 0 (the machine's physical memory) or, with
/// --allow-large, no limit.
std::uint64_t memory_limit(bool allow_large);

/// require_memory(estimate, memory_limit(allow_large), what), its InvalidInput completed with
/// the way out: "...; --allow-large tries anyway".
void require_memory_unless_allowed(double estimated_bytes, bool allow_large, const char* what);

}  // namespace fissure::cli
