// "Each slab's pattern differs, and their statistics share a distribution" (issue 13): six slabs
// of one material, each with its own seed, break into different patterns whose Eq. 5 distances
// to one another are smaller than their distances to slabs of another material. A failure of
// propagation (every slab the same seed, or a material's parameters lost on the way) or a
// material that scatters as widely as two materials differ fails it.

#include "fissure/exemplar/pattern_stats.hpp"
#include "fissure/exemplar/similarity.hpp"
#include "fissure/fracture/visible_pattern.hpp"
#include "fissure/io/scene_export.hpp"
#include "fissure/io/scene_import.hpp"
#include "fissure/scene/demo_scenes.hpp"
#include "fissure/scene/scene_fracture.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <set>

namespace fissure {
namespace {

namespace fs = std::filesystem;

// The visible pattern statistics of every slab of the 3 × 2 street fractured with `material`.
std::vector<PatternStats> slab_statistics(const ImportedScene& scene, const std::string& material) {
  SceneFractureOptions options;
  options.assignments.by_material["concrete"] = material;
  options.target_tets = 1500;
  options.threads = 2;
  std::mutex mutex;
  std::map<std::string, TetMesh> meshes;  // by the surface's name, which ends in the body's path
  options.mesher = [&](const SurfaceMesh& surface, const TetrahedralizeOptions& o) {
    TetMesh mesh = tetrahedralize(surface, o);
    const std::lock_guard<std::mutex> lock(mutex);
    meshes[surface.source_name] = mesh;
    return mesh;
  };
  const SceneFracture run = fracture_scene(scene, options);
  std::vector<PatternStats> out;
  for (std::size_t b = 0; b < run.bodies.size(); ++b) {
    if (!run.results[b]) {
      ADD_FAILURE() << run.reports[b].path << ": " << run.reports[b].reason;
      continue;
    }
    const auto mesh = std::find_if(meshes.begin(), meshes.end(), [&](const auto& m) {
      return m.first.size() >= run.reports[b].path.size() &&
             m.first.compare(m.first.size() - run.reports[b].path.size(), std::string::npos, run.reports[b].path) == 0;
    });
    if (mesh == meshes.end()) {
      ADD_FAILURE() << run.reports[b].path << " was not meshed";
      continue;
    }
    const std::vector<CrackSurface>& cracks = run.results[b]->fracture.result.cracks;
    const VisiblePattern pattern =
        extract_visible_pattern(mesh->second, cracks, static_cast<int>(cracks.size()), Eigen::Vector3d::UnitY());
    EXPECT_TRUE(pattern.has_visible_face) << pattern.empty_reason;
    out.push_back(compute_pattern_stats(pattern.graph, pattern.stats_options));
  }
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

TEST(SlabStatistics, SlabsOfOneMaterialDifferButShareADistribution) {
  const fs::path dir = test::fresh_temp_dir("slab-statistics");
  DemoStreetOptions o;
  o.slabs_along = 3;
  o.slabs_across = 2;
  o.curb_and_road = false;
  write_scene(dir / "street.glb", demo_street(o));
  const ImportedScene scene = import_scene(dir / "street.glb");
  const std::vector<PatternStats> tiles = slab_statistics(scene, "ceramic-tile");
  const std::vector<PatternStats> glass = slab_statistics(scene, "glass");
  ASSERT_EQ(tiles.size(), 6u);
  ASSERT_EQ(glass.size(), 6u);

  // Different: no two slabs break into the same pattern.
  std::set<std::vector<double>> areas;
  for (const PatternStats& s : tiles) areas.insert(s.fragment_areas);
  EXPECT_EQ(areas.size(), tiles.size()) << "two slabs broke the same way";

  // One distribution: every tile slab is nearer (median Eq. 5) to the other tile slabs than to
  // the glass slabs, and the tiles' typical spread is well below the two materials' distance.
  std::vector<double> within_all, across_all;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    std::vector<double> within, across;
    for (std::size_t j = 0; j < tiles.size(); ++j)
      if (j != i) within.push_back(pattern_similarity(tiles[i], tiles[j]).total);
    for (const PatternStats& g : glass) across.push_back(pattern_similarity(tiles[i], g).total);
    EXPECT_LT(median(within), median(across)) << "tile slab " << i << " (" << tiles[i].fragment_count << " fragments)";
    within_all.insert(within_all.end(), within.begin(), within.end());
    across_all.insert(across_all.end(), across.begin(), across.end());
  }
  EXPECT_LT(median(within_all), 0.75 * median(across_all))
      << "within " << median(within_all) << ", across " << median(across_all);
  std::printf("Eq. 5 median: between tile slabs %.3f, tile to glass %.3f\n", median(within_all), median(across_all));
}

}  // namespace
}  // namespace fissure
