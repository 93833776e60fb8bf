// Mesh independence (issue 10): a material fitted on one body is applied to bodies of other
// resolutions, so the same parameters must give the same kind of pattern on a coarse and a fine
// mesh of one body. The bundled tile material on the 1 × 1 × 0.05 m tile meshed by CGAL at about
// 7K, 24K and 54K tets, default scenario, seeds 1–10: the Eq. 5 distance between the 7K and the
// 54K pattern of the same seed (the resistance field is a function of position: one seed is one
// body) must stay within 1.5× the seed-to-seed spread at 54K (the mean distance over the 45
// pairs of seeds), the bound. Ten seeds, not six: with six the ratio moved by ±0.2 from
// one crack_turning to the next (1.31–1.72), more than the margin it is tested against.
// Labelled slow: three CGAL meshes and 30 runs, ~15 s.
//
// With one independent resistance draw per element (resistance_correlation = 0, the paper's) the
// ratio is 7.4: a finer mesh has more weak elements and breaks into more fragments (202, 253,
// 331 visible at 7K, 24K, 54K). docs/fracture.md ("Mesh independence") has the measurements.
#include "fissure/exemplar/similarity.hpp"
#include "fissure/fracture/material_file.hpp"
#include "fissure/fracture/visible_pattern.hpp"
#include "fissure/mesh/tetrahedralize.hpp"
#include "fissure/mesh/tile.hpp"

#include "fracture_test_bodies.hpp"

#include <cstdio>
#include <memory>
#include <vector>

namespace fissure {
namespace {

constexpr int kSeeds = 10;

std::vector<PatternStats> patterns(int target_tets, const FractureParams& params) {
  TetrahedralizeOptions options;
  options.target_tets = target_tets;
  auto mesh = std::make_shared<const TetMesh>(tetrahedralize(make_tile_surface({1.0, 1.0, 0.05}), options));
  const PreparedBody body(mesh, params.elastic(), FractureScenario{});
  std::vector<PatternStats> out;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const test::DefaultRun run = test::run_default_scenario(body, params, static_cast<std::uint64_t>(seed));
    const VisiblePattern p = extract_visible_pattern(*mesh, run.result.cracks, static_cast<int>(run.result.cracks.size()),
                                                     Eigen::Vector3d::UnitZ());
    out.push_back(compute_pattern_stats(p.graph, p.stats_options));
  }
  std::printf("%6d tets: visible fragments", mesh->tet_count());
  for (const PatternStats& s : out) std::printf(" %d", s.fragment_count);
  std::printf("\n");
  return out;
}

TEST(MeshIndependence, CoarseAndFineMeshesOfOneTileGiveTheSamePattern) {
  const FractureParams params = load_material(find_material(kDefaultMaterialName)).params;
  const std::vector<PatternStats> coarse = patterns(7000, params), middle = patterns(24000, params),
                                  fine = patterns(54000, params);
  double spread = 0.0;
  int pairs = 0;
  for (int a = 0; a < kSeeds; ++a)
    for (int b = a + 1; b < kSeeds; ++b, ++pairs) spread += pattern_similarity(fine[a], fine[b]).total;
  spread /= pairs;
  double to_coarse = 0.0, to_middle = 0.0;
  for (int s = 0; s < kSeeds; ++s) {
    to_coarse += pattern_similarity(coarse[s], fine[s]).total / kSeeds;
    to_middle += pattern_similarity(middle[s], fine[s]).total / kSeeds;
  }
  std::printf("Eq. 5 to the 54K pattern of the same seed: 7K %.3f, 24K %.3f; seed spread at 54K %.3f "
              "(ratios %.2f, %.2f)\n",
              to_coarse, to_middle, spread, to_coarse / spread, to_middle / spread);
  EXPECT_LE(to_coarse, 1.5 * spread);
  EXPECT_LE(to_middle, 1.5 * spread);
}

}  // namespace
}  // namespace fissure
