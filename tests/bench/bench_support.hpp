#pragma once
// Meshes and load cases shared by the benchmarks: the paper's 1 × 1 × 0.05 m tile at three
// resolutions, corner supports and a 5 cm centre patch (performance.md §5).

#include "fissure/fem/elastic_body.hpp"
#include "fissure/fem/load.hpp"
#include "fissure/fem/static_solver.hpp"
#include "fissure/fem/supports.hpp"
#include "fissure/mesh/tetrahedralize.hpp"
#include "fissure/mesh/tile.hpp"

#include <map>
#include <memory>
#include <sys/resource.h>

namespace fissure::bench {

/// The CGAL tile with about `target` tets, meshed anew on every call.
inline std::shared_ptr<const TetMesh> make_tile_mesh(int target) {
  TetrahedralizeOptions options;
  options.target_tets = target;
  return std::make_shared<const TetMesh>(tetrahedralize(make_tile_surface({1.0, 1.0, 0.05}), options));
}

/// The CGAL tile with about `target` tets (built once per process).
inline std::shared_ptr<const TetMesh> tile(int target) {
  static std::map<int, std::shared_ptr<const TetMesh>> cache;
  auto& slot = cache[target];
  if (!slot) slot = make_tile_mesh(target);
  return slot;
}

/// Bottom nodes within 5 cm of the four corners, fixed in x, y, z.
inline std::vector<int> corner_supports(const TetMesh& mesh) {
  std::vector<SupportSpec> specs;
  for (const char* s : {"box:-0.5,-0.45,-0.5,-0.45,0,0", "box:0.45,0.5,-0.5,-0.45,0,0", "box:-0.5,-0.45,0.45,0.5,0,0",
                        "box:0.45,0.5,0.45,0.5,0,0"}) {
    specs.push_back(parse_support(s));
  }
  return resolve_supports(mesh, specs);
}

/// 10 kN down on the top faces within 5 cm of the centre.
inline Eigen::VectorXd centre_patch(const TetMesh& mesh) {
  return assemble_load(mesh, parse_load("ball:0,0,0.05,0.05=0,0,-1e4"));
}

/// The direct solution of the standard load case (corner supports, centre patch) on `body`.
inline Eigen::VectorXd centre_patch_displacement(const std::shared_ptr<const ElasticBody>& body) {
  const TetMesh& mesh = body->mesh();
  return StaticSolver(body, corner_supports(mesh)).solve(centre_patch(mesh)).displacement;
}

/// Peak resident set of this process so far, MB.
inline double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace fissure::bench
