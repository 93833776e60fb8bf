#include "fissure/fracture/simulation.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/mesh/structured_box.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace fissure {
namespace {

std::shared_ptr<const FractureBody> box_body(const Eigen::Vector3d& size, int nx, int ny, int nz) {
  return std::make_shared<const FractureBody>(
      std::make_shared<const TetMesh>(make_structured_box(Eigen::Vector3d::Zero(), size, nx, ny, nz)));
}

// A ceramic-like material with no relaxation, no rate and no noise: each test turns on what it
// exercises. Flaw size a_f = (K/R)²/π = 3.5 cm.
FractureParams plain_params() {
  FractureParams p;
  p.youngs_modulus = 3.0e10;
  p.poisson_ratio = 0.2;
  p.density = 2400.0;
  p.resistance_mean = 3.0e6;
  p.fracture_toughness = 1.0e6;
  p.age = 1.0;
  p.stress_rate = 0.0;
  p.relax_radius = 0.05;
  p.relax_rate = 0.0;
  p.resistance_stddev = 0.0;
  p.load_factor = 0.0;
  p.noise = {};
  p.relaxation = RelaxationChoice::Directional;
  return p;
}

StressField uniform_stress(int tets, const Eigen::Matrix<double, 6, 1>& s) {
  StressField f(tets, 6);
  for (int t = 0; t < tets; ++t) f.row(t) = s.transpose();
  return f;
}

// Resistances R_cm·(1 + c·u), u uniform in [−1, 1): small flaws that break ties the way a real
// material does.
Eigen::VectorXd resistances(int tets, double mean, double spread, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::VectorXd r(tets);
  for (double& x : r) x = mean * (1.0 + spread * rng.uniform(-1.0, 1.0));
  return r;
}

TEST(RelaxationKernel, OneAtTheCrackZeroAtTheRadiusAndSmooth) {
  const double r = 0.07;
  EXPECT_DOUBLE_EQ(relaxation_kernel(0.0, r), 1.0);
  EXPECT_EQ(relaxation_kernel(r, r), 0.0);
  EXPECT_EQ(relaxation_kernel(2 * r, r), 0.0);
  // Flat at both ends: the one-sided difference quotients vanish to O(h) at 0 and O(h²) at r.
  const double h = 1e-6 * r;
  EXPECT_LT(std::abs(relaxation_kernel(h, r) - 1.0) / h, 1e-4);
  EXPECT_LT(relaxation_kernel(r - h, r) / h, 1e-9);
  for (double d = 0.0; d < r; d += r / 100) EXPECT_GE(relaxation_kernel(d, r), relaxation_kernel(d + r / 100, r));
}

// Uniaxial tension σ_xx above the resistance everywhere in a bar along x (the analytic field of
// an end-loaded bar): every crack must open perpendicular to the load, and cross the bar.
TEST(FractureSimulation, BarInTensionCracksPerpendicularToTheLoad) {
  const auto body = box_body({1.0, 0.1, 0.1}, 40, 4, 4);
  FractureParams p = plain_params();
  p.relax_rate = p.resistance_mean;  // relax enough that cracks space out
  p.relax_radius = 0.15;
  Eigen::Matrix<double, 6, 1> s;
  s << 1.2 * p.resistance_mean, 0, 0, 0, 0, 0;
  const int n = body->mesh().tet_count();
  const FractureResult r = simulate_fracture(*body, p, uniform_stress(n, s), resistances(n, p.resistance_mean, 0.05, 1), 7);
  ASSERT_GE(r.cracks.size(), 2u);
  for (const CrackSurface& c : r.cracks) {
    EXPECT_GT(std::abs(c.normal.x()), 0.999) << "crack " << c.id;
    // A 0.1 × 0.1 section cut straight through holds 4·4 cells · 6 tets worth of polygons with
    // area 0.01 m²; the crack may end on an earlier one, so at least the section's area.
    EXPECT_NEAR(c.area, 0.01, 1e-9) << "crack " << c.id;
  }
  EXPECT_EQ(r.fragments.count, static_cast<int>(r.cracks.size()) + 1);
  EXPECT_TRUE(r.partial_cracks.empty());
}

TEST(FractureSimulation, NothingCracksBelowResistance) {
  const auto body = box_body({1.0, 0.1, 0.1}, 20, 2, 2);
  FractureParams p = plain_params();
  Eigen::Matrix<double, 6, 1> s;
  s << 0.99 * p.resistance_mean, 0.5 * p.resistance_mean, 0, 0, 0, 0;
  const int n = body->mesh().tet_count();
  const FractureResult r = simulate_fracture(*body, p, uniform_stress(n, s), Eigen::VectorXd::Constant(n, p.resistance_mean), 7);
  EXPECT_TRUE(r.cracks.empty());
  EXPECT_EQ(r.fragments.count, 1);
}

// High stress in the first fifth of a bar, none beyond: the crack opens there, and the energy
// budget it gathers there lets it run at most a short way into the unstressed part.
TEST(FractureSimulation, CracksArrestInALowStressRegion) {
  const auto body = box_body({1.0, 0.4, 0.02}, 50, 20, 1);
  FractureParams p = plain_params();
  const TetMesh& mesh = body->mesh();
  StressField f = StressField::Zero(mesh.tet_count(), 6);
  for (int t = 0; t < mesh.tet_count(); ++t) {
    if (mesh.centroid(t).x() < 0.2) f(t, 1) = 1.5 * p.resistance_mean;  // σ_yy: cracks run along x
  }
  const FractureResult r = simulate_fracture(*body, p, f, resistances(mesh.tet_count(), p.resistance_mean, 0.05, 3), 11);
  ASSERT_FALSE(r.cracks.empty());
  double reach = 0.0;
  for (const CrackSurface& c : r.cracks) {
    for (const CrackCut& cut : c.cuts) reach = std::max(reach, mesh.centroid(cut.tet).x());
  }
  EXPECT_GT(reach, 0.1);
  EXPECT_LT(reach, 0.5) << "cracks ran far into the unstressed region";
  // They open at x = 0 and end inside: partial cracks, which separate nothing.
  EXPECT_EQ(r.partial_cracks.size(), r.cracks.size());
  EXPECT_EQ(r.fragments.count, 1);
}

// A plate under the in-plane stress increase only, with scattered resistance and directional
// relaxation: the setting of the fit. Used by the tests below.
struct PlateCase {
  std::shared_ptr<const FractureBody> body = box_body({0.5, 0.5, 0.02}, 20, 20, 1);
  FractureParams params = plain_params();
  StressField initial;
  Eigen::VectorXd resistance;
  explicit PlateCase(std::uint64_t seed, double rate_factor = 1.3) {
    params.stress_rate = rate_factor * params.resistance_mean;
    params.relax_rate = 0.3 * params.resistance_mean;
    params.relax_radius = 0.06;
    params.noise[0] = {0.004, 20.0};
    const int n = body->mesh().tet_count();
    initial = StressField::Zero(n, 6);
    resistance = resistances(n, params.resistance_mean, 0.3, seed);
  }
  FractureResult run(std::uint64_t seed, SimulationOptions options = {}) const {
    return simulate_fracture(*body, params, initial, resistance, seed, options);
  }
};

// The event queue against Algorithm 1 as printed, with a small step: the same cracks from the
// same elements in the same order, each within one step of the event time (the fixed-step run
// tests only at multiples of Δt).
TEST(FractureSimulation, EventDrivenAgreesWithFixedStepsAsTheStepShrinks) {
  PlateCase plate(5);
  // Up to the age at which the weakest elements (R = 0.7 R_cm) have crossed: about a hundred
  // cracks, the early stage where events are distinct; later ones depend on all before them.
  plate.params.age = 0.62;
  // Single cracks only. Under the plate's equi-biaxial stress increase most cracks open as stars
  // (star_biaxiality 0.7), and a star's arms follow the principal direction of a stress whose two
  // in-plane values are nearly equal, which the one-step difference in opening time turns by up
  // to 1e-5 rad: in the sanitizer build 5 of ~100 normals missed the 1e-6 below. Open in issue 10.
  plate.params.star_biaxiality = 1.0;
  const FractureResult events = plate.run(3);
  ASSERT_GE(events.cracks.size(), 5u);
  SimulationOptions fixed;
  // 32,000 steps: a turning crack's path reads the stress map at its opening time, so a step
  // late it bends by up to dσ_e·Δt more, and can cut another tet; at 8,000 steps that moved crack
  // 96 of ~100 by ten steps, at 32,000 no crack.
  fixed.fixed_time_step = plate.params.age / 32000;
  const FractureResult steps = plate.run(3, fixed);
  ASSERT_EQ(steps.cracks.size(), events.cracks.size());
  for (std::size_t i = 0; i < events.cracks.size(); ++i) {
    EXPECT_EQ(steps.cracks[i].origin_tet, events.cracks[i].origin_tet) << "crack " << i;
    // Within one step either way: the fixed-step run opens a crack up to Δt late, and where
    // the relaxation clamp binds (it removes all the tension along d̂, however much there is)
    // the stress left differs by up to dσ_e·Δt, which moves the crossings of later cracks by up
    // to a step either way (crack 111 of 119 here opened 5e-6 earlier at Δt = 7.75e-5). Exactly
    // ordered times would only hold for identical histories.
    EXPECT_GE(steps.cracks[i].time, events.cracks[i].time - fixed.fixed_time_step - 1e-12) << "crack " << i;
    EXPECT_LE(steps.cracks[i].time, events.cracks[i].time + fixed.fixed_time_step + 1e-12);
    // The same tets flooded, and a plane turned by no more than the stress moves in one step
    // (dσ·Δt ≈ 1e-4 R_cm against the ≈ R_cm deviatoric stress that sets the direction).
    EXPECT_EQ(steps.cracks[i].cuts.size(), events.cracks[i].cuts.size()) << "crack " << i;
    EXPECT_GT(std::abs(steps.cracks[i].normal.dot(events.cracks[i].normal)), 1.0 - 1e-6) << "crack " << i;
  }
  // Fragment counts are not compared: a plane turned by 1e-4 rad can move a sliver piece from one
  // side of a probe point to the other (fracture_result.hpp), which is resolution, not Algorithm 1.
}

TEST(FractureSimulation, SameSeedSameBytes) {
  const PlateCase plate(9);
  const FractureResult a = plate.run(4), b = plate.run(4), c = plate.run(5);
  ASSERT_EQ(a.cracks.size(), b.cracks.size());
  for (std::size_t i = 0; i < a.cracks.size(); ++i) {
    ASSERT_EQ(a.cracks[i].cuts.size(), b.cracks[i].cuts.size());
    EXPECT_EQ(a.cracks[i].time, b.cracks[i].time);
    for (std::size_t j = 0; j < a.cracks[i].cuts.size(); ++j) {
      EXPECT_EQ(a.cracks[i].cuts[j].tet, b.cracks[i].cuts[j].tet);
      EXPECT_EQ(a.cracks[i].cuts[j].node_values, b.cracks[i].cuts[j].node_values);
    }
  }
  EXPECT_EQ(a.fragments.fragment_of_tet, b.fragments.fragment_of_tet);
  // Another seed re-rolls the noise, so the crack surfaces differ.
  bool differs = a.cracks.size() != c.cracks.size();
  for (std::size_t i = 0; i < std::min(a.cracks.size(), c.cracks.size()) && !differs; ++i) {
    differs = a.cracks[i].cuts.size() != c.cracks[i].cuts.size() ||
              a.cracks[i].cuts[0].node_values != c.cracks[i].cuts[0].node_values;
  }
  EXPECT_TRUE(differs);
}

// Statistical, over seeds: a faster stress increase opens more cracks by the same age, and more
// fragments. Eight seeds per setting; the rates differ by 2×, which on this plate moves the
// mean fragment count far more than its seed-to-seed spread.
TEST(FractureSimulation, FasterStressIncreaseGivesMoreFragments) {
  double slow = 0, fast = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    slow += PlateCase(seed, 1.2).run(seed).fragments.count;
    fast += PlateCase(seed, 2.4).run(seed).fragments.count;
  }
  EXPECT_GT(fast, 1.3 * slow) << "slow " << slow / 8 << ", fast " << fast / 8;
}

TEST(FractureSimulation, BadInputsNameTheCulprit) {
  const PlateCase plate(1);
  const int n = plate.body->mesh().tet_count();
  auto message = [&](auto&& call) {
    try {
      call();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(message([&] { simulate_fracture(*plate.body, plate.params, StressField::Zero(n - 1, 6), plate.resistance, 1); })
                .find("rows"),
            std::string::npos);
  Eigen::VectorXd r = plate.resistance;
  r[17] = -1.0;
  EXPECT_NE(message([&] { simulate_fracture(*plate.body, plate.params, plate.initial, r, 1); }).find("tet 18"),
            std::string::npos);
  StressField f = plate.initial;
  f(4, 2) = std::nan("");
  EXPECT_NE(message([&] { simulate_fracture(*plate.body, plate.params, f, plate.resistance, 1); }).find("tet 5"),
            std::string::npos);
  FractureParams p = plate.params;
  p.relax_radius = -1.0;
  EXPECT_NE(message([&] { simulate_fracture(*plate.body, p, plate.initial, plate.resistance, 1); }).find("relax_radius"),
            std::string::npos);
  p = plate.params;
  p.relaxation = RelaxationChoice::FromExemplar;
  EXPECT_NE(message([&] { simulate_fracture(*plate.body, p, plate.initial, plate.resistance, 1); }).find("exemplar"),
            std::string::npos);
}

// Equi-biaxial tension (the in-plane stress increase alone, one resistance everywhere): the
// largest principal stress is repeated, so any in-plane direction is a principal one. The
// eigensolver alone always returned the same axis and the plate filled with parallel cracks
// (mean junction angle 10°); the direction is drawn in that plane instead, so the normals
// spread: for uniform angles the mean |cos| between two normals is 2/π ≈ 0.64, for parallel
// cracks 1.
TEST(FractureSimulation, RepeatedPrincipalStressOpensCracksInEveryDirection) {
  PlateCase plate(5);
  plate.resistance.setConstant(plate.params.resistance_mean);
  plate.params.relax_rate = 0.0;  // nothing breaks the symmetry of the stress
  plate.params.age = 2.0;
  const FractureResult r = plate.run(3);
  ASSERT_GE(r.cracks.size(), 10u);
  double sum = 0.0;
  int pairs = 0;
  for (std::size_t i = 0; i < r.cracks.size(); ++i)
    for (std::size_t j = i + 1; j < r.cracks.size(); ++j, ++pairs) sum += std::abs(r.cracks[i].normal.dot(r.cracks[j].normal));
  EXPECT_LT(sum / pairs, 0.8) << r.cracks.size() << " cracks";
}

}  // namespace
}  // namespace fissure
