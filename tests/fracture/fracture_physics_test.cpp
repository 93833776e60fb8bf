// The simulation's physics, statistically over seeds (issue 10, "How it is shown to work"):
// directional relaxation (Eq. 3) gives T junctions nearer 90° on the visible face than isotropic
// relaxation (Eq. 4), isotropic relaxation more Y junctions, and a larger load factor l more
// fragments. Each claim compares means
// over seeds against a margin of twice the standard error of their difference, measured here
// from the seed-to-seed spread and printed, so a failure says by how much. The runs are
// deterministic (fixed seeds); the margin is what keeps the claim true for any other equally
// valid set of seeds or a harmless change of the simulation's round-off.
#include "fracture_test_bodies.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

namespace fissure {
namespace {

// Mean and standard error of the mean of per-seed values.
struct Sample {
  std::vector<double> values;
  double mean() const {
    double s = 0.0;
    for (double v : values) s += v;
    return s / static_cast<double>(values.size());
  }
  double standard_error() const {
    const double m = mean();
    double s = 0.0;
    for (double v : values) s += (v - m) * (v - m);
    const auto n = static_cast<double>(values.size());
    return std::sqrt(s / (n - 1.0) / n);
  }
};

double margin(const Sample& a, const Sample& b) {
  return 2.0 * std::hypot(a.standard_error(), b.standard_error());
}

struct Tally {
  Sample angle_distance;  // |mean T junction angle − 90°| per seed
  Sample t_fraction, y_fraction, fragments;
  long t = 0, y = 0, x = 0;
};

Tally tally(const PreparedBody& body, const FractureParams& p, int seeds) {
  Tally t;
  for (int seed = 1; seed <= seeds; ++seed) {
    const test::DefaultRun run = test::run_default_scenario(body, p, static_cast<std::uint64_t>(seed));
    const PatternStats s = test::expect_sane_pattern(body.mesh(), run.result, "seed " + std::to_string(seed));
    t.fragments.values.push_back(run.result.fragments.count);
    const int junctions = s.t_count + s.y_count + s.x_count;
    t.t += s.t_count;
    t.y += s.y_count;
    t.x += s.x_count;
    if (junctions == 0) continue;
    // The meeting angle of the Ts (their smallest gap): a Y's smallest gap, near 120°, says
    // nothing about how squarely a crack meets the one it ends on.
    double sum = 0.0;
    int ts = 0;
    for (const JunctionStat& j : s.junctions) {
      if (j.type != JunctionType::T) continue;
      sum += j.angle_deg;
      ++ts;
    }
    if (ts > 0) t.angle_distance.values.push_back(std::abs(sum / ts - 90.0));
    t.t_fraction.values.push_back(static_cast<double>(s.t_count) / junctions);
    t.y_fraction.values.push_back(static_cast<double>(s.y_count) / junctions);
  }
  return t;
}

// The default tile (ceramic defaults, default load, 1 cm cells) with both relaxations, 20 seeds
// each: ~970 and ~440 junctions in all. 20, not 12: star cracks' arms meet earlier cracks less
// squarely than turning single cracks, and with 12 seeds the Eq. 3 against Eq. 4 difference of
// the T angles (5.8°) was within a tenth of a degree of its margin.
// With them, the paper's straight cracks (crack_turning 0) under Eq. 3.
struct RelaxationComparison {
  Tally directional, isotropic, straight;
  RelaxationComparison() {
    const PreparedBody body(test::plate_mesh({0.4, 0.4, 0.02}, 40, 40, 1), FractureParams{}.elastic(),
                            FractureScenario{});
    FractureParams p;
    p.relaxation = RelaxationChoice::Directional;
    directional = tally(body, p, kSeeds);
    p.relaxation = RelaxationChoice::Isotropic;
    isotropic = tally(body, p, kSeeds);
    p.relaxation = RelaxationChoice::Directional;
    p.crack_turning = 0.0;
    straight = tally(body, p, kSeeds);
    print("directional", directional);
    print("isotropic", isotropic);
    print("straight", straight);
  }
  static void print(const char* name, const Tally& t) {
    std::printf("%-11s |angle - 90| %.1f ± %.1f° (s.e.), T %ld Y %ld X %ld, T fraction %.3f ± %.3f, Y fraction %.3f ± "
                "%.3f, fragments %.1f\n",
                name, t.angle_distance.mean(), t.angle_distance.standard_error(), t.t, t.y, t.x, t.t_fraction.mean(),
                t.t_fraction.standard_error(), t.y_fraction.mean(), t.y_fraction.standard_error(), t.fragments.mean());
  }
  static constexpr int kSeeds = 20;
};

const RelaxationComparison& comparison() {
  static const RelaxationComparison c;
  return c;
}

// Eq. 3 removes the stress along the crack normal, so the next crack nearby runs across it,
// and a turning crack closing in on an earlier one turns to meet it square; Eq. 4 removes
// stress in every direction and leaves the next crack's direction to the load and the flaws.
// Measured over the T junctions (20 seeds): |angle − 90°| 22.9 ± 1.1° against 29.4 ± 1.6°, a
// difference of 6.5° against a margin of 3.9°. (Before star cracks, on 2 cm cells, 13.0° against
// 32.3°: Eq. 4 now opens most cracks as stars, and fewer Ts are left to skew; star arms run
// straight from their kink and meet earlier cracks less squarely than turning single cracks.)
TEST(FracturePhysics, DirectionalRelaxationGivesJunctionsNearerRightAngles) {
  const RelaxationComparison& c = comparison();
  ASSERT_EQ(c.directional.angle_distance.values.size(), static_cast<std::size_t>(RelaxationComparison::kSeeds));
  ASSERT_EQ(c.isotropic.angle_distance.values.size(), static_cast<std::size_t>(RelaxationComparison::kSeeds));
  EXPECT_GT(c.isotropic.angle_distance.mean() - c.directional.angle_distance.mean(),
            margin(c.directional.angle_distance, c.isotropic.angle_distance));
}

// Crack paths (docs/fracture.md): cracks that turn toward the principal direction, which near an
// earlier crack lies along it, meet it nearer a right angle than the paper's planes, which keep
// the direction they opened with. Measured over the T junctions (20 seeds): |angle − 90°|
// 22.9 ± 1.1° turning against 28.1 ± 1.0° straight (Eq. 3 both), a difference of 5.2° against a
// margin of 3.0°.
TEST(FracturePhysics, TurningCracksMeetEarlierOnesNearerRightAngles) {
  const RelaxationComparison& c = comparison();
  ASSERT_EQ(c.straight.angle_distance.values.size(), static_cast<std::size_t>(RelaxationComparison::kSeeds));
  EXPECT_GT(c.straight.angle_distance.mean() - c.directional.angle_distance.mean(),
            margin(c.directional.angle_distance, c.straight.angle_distance));
}

// A crack meeting an earlier one ends on it in a T, whatever the relaxation; Ys come from star
// cracks (docs/fracture.md), which open where the in-plane stress at the origin is biaxial enough
// (λ₂/λ₁ ≥ star_biaxiality, 0.7 by default). Both relaxations and the stress increase remove or
// add the same stress in every in-plane direction except Eq. 3, which removes the normal stress
// across a crack: it leaves the stress near a crack pulling along it, and the next crack there
// opens single, in a T. Eq. 4 keeps λ₁ − λ₂ as the load made it, and more cracks open as stars.
// Measured (20 seeds): Y fraction 0.275 ± 0.014 (Eq. 4) against 0.167 ± 0.007 (Eq. 3), a
// difference of 0.108 against a margin of 0.031; T fraction 0.708 ± 0.014 against 0.802 ± 0.010
// (difference 0.094, margin 0.034). Before star cracks: 0 and 2 Y junctions in 12 seeds.
TEST(FracturePhysics, IsotropicRelaxationGivesMoreYJunctions) {
  const RelaxationComparison& c = comparison();
  EXPECT_GT(c.directional.t_fraction.mean() - c.isotropic.t_fraction.mean(),
            margin(c.directional.t_fraction, c.isotropic.t_fraction));
  EXPECT_GT(c.isotropic.y_fraction.mean() - c.directional.y_fraction.mean(),
            margin(c.directional.y_fraction, c.isotropic.y_fraction));
}

// A larger load factor gives more fragments (the dσ_e half is simulation_test's
// FasterStressIncreaseGivesMoreFragments). With the ceramic defaults the default load at l = 30
// reaches ~5 MPa, a tenth of R_cm, and dσ_e decides everything (l = 10 and l = 30 both give 36.8
// fragments on average over 8 seeds, ± 2.4 and ± 3.4 s.e.); so here the load acts alone (dσ_e = 0) on a material it can break: R_cm = 1 MPa,
// R_cvar and v_relax the Table 3 fractions 15 % and 20 % of it. Measured (16 seeds, s.e.): 1.38 ± 0.15
// fragments at l = 20 against 2.50 ± 0.30 at l = 30, a difference of 1.12 against a margin of 0.67.
// (With one energy budget per crack the difference was 5.0; since each path carries its own,
// decaying over r_relax, load cracks from the centre arrest sooner, and 8 seeds no longer
// separate the means: 0.88 against 1.06.)
TEST(FracturePhysics, LargerLoadFactorGivesMoreFragments) {
  const PreparedBody body(test::plate_mesh({0.4, 0.4, 0.02}, 20, 20, 1), FractureParams{}.elastic(), FractureScenario{});
  FractureParams p;
  p.stress_rate = 0.0;
  p.resistance_mean = 1e6;
  p.resistance_stddev = 0.15 * p.resistance_mean;
  p.relax_rate = 0.2 * p.resistance_mean;
  constexpr int kSeeds = 16;
  p.load_factor = 20.0;
  const Tally low = tally(body, p, kSeeds);
  p.load_factor = 30.0;
  const Tally high = tally(body, p, kSeeds);
  std::printf("fragments: l = 20 %.2f ± %.2f (s.e.), l = 30 %.2f ± %.2f\n", low.fragments.mean(),
              low.fragments.standard_error(), high.fragments.mean(), high.fragments.standard_error());
  EXPECT_GT(high.fragments.mean() - low.fragments.mean(), margin(low.fragments, high.fragments));
  // Below the load that breaks the tile at all, nothing does.
  p.load_factor = 5.0;
  EXPECT_EQ(tally(body, p, 2).fragments.mean(), 1.0);
}

}  // namespace
}  // namespace fissure
