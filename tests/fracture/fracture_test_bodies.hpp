#pragma once
// Bodies and checks the fracture stability, physics and slow tests share: a structured plate
// prepared with the default scenario (rim rollers, a centre patch load), and the invariants every
// FractureResult must hold whatever the parameters.
#include "fissure/fracture/prepared_body.hpp"
#include "fissure/fracture/resistance_field.hpp"
#include "fissure/fracture/simulation.hpp"
#include "fissure/fracture/visible_pattern.hpp"
#include "fissure/mesh/structured_box.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

namespace fissure::test {

inline std::shared_ptr<const TetMesh> plate_mesh(const Eigen::Vector3d& size, int nx, int ny, int nz) {
  return std::make_shared<const TetMesh>(make_structured_box(Eigen::Vector3d::Zero(), size, nx, ny, nz));
}

// One run of the default scenario: σ⁰ of the default load for `params`, resistance drawn from
// (R_cm, R_cvar) with `seed`, the simulation with the same seed.
struct DefaultRun {
  FractureResult result;
  StressField initial;
};

inline DefaultRun run_default_scenario(const PreparedBody& body, const FractureParams& params, std::uint64_t seed,
                                       const SimulationOptions& options = {}) {
  DefaultRun run;
  run.initial = body.initial_stress(params);
  const Eigen::VectorXd resistance = draw_resistance(body.mesh().centroids(), params, seed);
  run.result = simulate_fracture(body.fracture_body(), params, run.initial, resistance, seed, options);
  return run;
}

// The invariants of any result: finite numbers everywhere, times in [0, age] in order, cut tets
// and labels in range, junctions only on earlier cracks, at most max_cracks cracks and the limit
// flag set exactly when it stopped the run. `what` names the case in failures.
inline void expect_sane_result(const TetMesh& mesh, const FractureParams& params, const SimulationOptions& options,
                               const FractureResult& r, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_LE(static_cast<int>(r.cracks.size()), options.max_cracks);
  if (r.crack_limit_reached) {
    EXPECT_EQ(static_cast<int>(r.cracks.size()), options.max_cracks);
    EXPECT_LE(r.simulated_age, params.age);
    if (!r.cracks.empty()) {
      EXPECT_EQ(r.simulated_age, r.cracks.back().time);
    }
  } else {
    EXPECT_EQ(r.simulated_age, params.age);
  }
  double previous = 0.0;
  for (std::size_t k = 0; k < r.cracks.size(); ++k) {
    const CrackSurface& c = r.cracks[k];
    ASSERT_EQ(c.id, static_cast<int>(k));
    ASSERT_TRUE(std::isfinite(c.time)) << "crack " << k;
    EXPECT_GE(c.time, previous) << "crack " << k;
    EXPECT_GE(c.time, 0.0) << "crack " << k;
    EXPECT_LE(c.time, params.age) << "crack " << k;
    previous = c.time;
    ASSERT_TRUE(c.normal.allFinite()) << "crack " << k;
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-9) << "crack " << k;
    ASSERT_TRUE(c.origin.allFinite()) << "crack " << k;
    ASSERT_TRUE(std::isfinite(c.opening_stress)) << "crack " << k;
    ASSERT_TRUE(std::isfinite(c.area) && c.area >= 0.0) << "crack " << k << " area " << c.area;
    ASSERT_FALSE(c.cuts.empty()) << "crack " << k;
    EXPECT_EQ(c.cuts[0].tet, c.origin_tet) << "crack " << k;
    for (const CrackCut& cut : c.cuts) {
      ASSERT_GE(cut.tet, 0);
      ASSERT_LT(cut.tet, mesh.tet_count());
      for (double v : cut.node_values) {
        ASSERT_TRUE(std::isfinite(v)) << "crack " << k << " " << mesh.tet_label(cut.tet);
        ASSERT_NE(v, 0.0) << "crack " << k << " " << mesh.tet_label(cut.tet);
      }
      if (cut.clipped_by >= 0) {
        EXPECT_LT(cut.clipped_by, static_cast<int>(k));
        EXPECT_TRUE(cut.clip_side == 1 || cut.clip_side == -1);
      }
    }
    for (int j : c.stopped_on) {
      EXPECT_GE(j, 0);
      EXPECT_LT(j, static_cast<int>(k));
    }
  }
  ASSERT_EQ(r.fragments.fragment_of_tet.size(), static_cast<std::size_t>(mesh.tet_count()));
  EXPECT_GE(r.fragments.count, 1);
  for (int label : r.fragments.fragment_of_tet) {
    ASSERT_GE(label, 0);
    ASSERT_LT(label, r.fragments.count);
  }
  for (int k : r.partial_cracks) {
    ASSERT_GE(k, 0);
    ASSERT_LT(k, static_cast<int>(r.cracks.size()));
  }
}

// The visible pattern and its statistics: every number finite (a NaN here would reach the fit's
// Eq. 5 distance).
inline PatternStats expect_sane_pattern(const TetMesh& mesh, const FractureResult& r, const std::string& what) {
  SCOPED_TRACE(what);
  const VisiblePattern v =
      extract_visible_pattern(mesh, r.cracks, static_cast<int>(r.cracks.size()), Eigen::Vector3d::UnitZ());
  EXPECT_TRUE(v.has_visible_face) << v.empty_reason;
  if (!v.has_visible_face) return {};
  const PatternStats s = compute_pattern_stats(v.graph, v.stats_options);
  EXPECT_TRUE(std::isfinite(s.mean_junction_angle_deg));
  EXPECT_TRUE(std::isfinite(s.total_crack_length));
  EXPECT_TRUE(std::isfinite(s.junction_density));
  EXPECT_GE(s.fragment_count, 1);
  for (double a : s.fragment_areas) EXPECT_TRUE(std::isfinite(a) && a > 0.0) << a;
  for (double l : s.crack_lengths) EXPECT_TRUE(std::isfinite(l) && l >= 0.0) << l;
  return s;
}

}  // namespace fissure::test
