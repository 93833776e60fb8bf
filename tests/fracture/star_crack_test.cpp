// Star cracks (docs/fracture.md, "Star cracks"): where the in-plane stress at a crack's origin is
// biaxial enough, the crack opens as three arms 120° apart, a Y on the visible face; where one
// direction pulls harder, as one crack. One event each, on a plate with one weakest element at
// its centre, so the arms run well clear of the edges.
#include "fracture_test_bodies.hpp"

#include "fissure/fracture/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace fissure {
namespace {

struct CentreFlaw {
  std::shared_ptr<const FractureBody> body =
      std::make_shared<const FractureBody>(test::plate_mesh({0.4, 0.4, 0.02}, 40, 40, 1));
  FractureParams params;
  Eigen::VectorXd resistance;
  CentreFlaw() {
    params.star_biaxiality = 0.7;
    params.relax_rate = 0.0;
    params.stress_rate = 0.0;
    params.load_factor = 0.0;
    params.noise = {};  // straight arms: their angles are the star's
    params.resistance_stddev = 0.0;
    const TetMesh& mesh = body->mesh();
    resistance = Eigen::VectorXd::Constant(mesh.tet_count(), params.resistance_mean);
    int centre = 0;
    const Eigen::Vector3d c(0.2, 0.2, 0.02);
    for (int t = 1; t < mesh.tet_count(); ++t)
      if ((mesh.centroid(t) - c).squaredNorm() < (mesh.centroid(centre) - c).squaredNorm()) centre = t;
    resistance(centre) = 0.9 * params.resistance_mean;
  }
  // The first event only under in-plane principal stresses (s_x, s_y): max_cracks 2 holds a star.
  FractureResult run(double sx, double sy) const {
    Eigen::Matrix<double, 6, 1> s;
    s << sx, sy, 0.0, 0.0, 0.0, 0.0;
    StressField initial(body->mesh().tet_count(), 6);
    for (Eigen::Index t = 0; t < initial.rows(); ++t) initial.row(t) = s.transpose();
    SimulationOptions options;
    options.max_cracks = 2;
    return simulate_fracture(*body, params, initial, resistance, 3, options);
  }
};

// Equi-biaxial stress between the weakest element's resistance and everyone else's: it alone
// cracks, as a star (two cracks, the second leaving the first's kink).
TEST(StarCrack, OpensAsThreeArmsAtAYUnderEquiBiaxialTension) {
  const CentreFlaw plate;
  const double r = plate.params.resistance_mean;
  const FractureResult result = plate.run(0.95 * r, 0.95 * r);
  ASSERT_EQ(result.cracks.size(), 2u);
  EXPECT_EQ(result.cracks[0].branch_of, -1);
  EXPECT_EQ(result.cracks[1].branch_of, 0);
  EXPECT_EQ(result.cracks[1].time, result.cracks[0].time);
  EXPECT_EQ(result.cracks[1].stopped_on, std::vector<int>{0});
  const PatternStats s = test::expect_sane_pattern(plate.body->mesh(), result, "star");
  ASSERT_EQ(s.junctions.size(), 1u);
  const JunctionStat& y = s.junctions[0];
  EXPECT_EQ(y.type, JunctionType::Y);
  ASSERT_EQ(y.gaps_deg.size(), 3u);
  // The arms leave the kink 120° apart, and the kink is a node of the mesh on the visible face,
  // where the P1 traces bend with the crack: straight arms come out exact (measured: 120.0° each;
  // with the kink inside a tet, 132.5°, 109.4°, 118.1°). 1°: far above round-off, far below the
  // 10–15° of a kink inside a tet.
  for (double g : y.gaps_deg) EXPECT_NEAR(g, 120.0, 1.0);
  std::printf("star gaps %.1f %.1f %.1f°, at (%.3f, %.3f)\n", y.gaps_deg[0], y.gaps_deg[1], y.gaps_deg[2],
              y.position.x(), y.position.y());
  // The three arms split the plate in three, on the visible face and through the body: three
  // fragments of about a third of the 9,600 tets each.
  EXPECT_EQ(s.fragment_count, 3);
  ASSERT_EQ(result.fragments.count, 3);
  std::vector<int> tets(3, 0);
  for (int f : result.fragments.fragment_of_tet) ++tets[static_cast<std::size_t>(f)];
  std::printf("fragments of %d %d %d tets\n", tets[0], tets[1], tets[2]);
  for (int n : tets) EXPECT_GT(n, 2500);
}

// The same stress with stars off (star_biaxiality 1, the paper's crack), and a stress that pulls
// harder one way (λ₂/λ₁ = 0.5 < 0.7): one straight crack, no junction.
TEST(StarCrack, OpensAsOneCrackWhereOneDirectionPullsHarder) {
  CentreFlaw plate;
  const double r = plate.params.resistance_mean;
  for (const auto& [biaxiality, sy] : {std::pair{1.0, 0.95}, std::pair{0.7, 0.475}}) {
    SCOPED_TRACE(biaxiality);
    plate.params.star_biaxiality = biaxiality;
    const FractureResult result = plate.run(0.95 * r, sy * r);
    ASSERT_EQ(result.cracks.size(), 1u);
    EXPECT_EQ(result.cracks[0].branch_of, -1);
    const PatternStats s = test::expect_sane_pattern(plate.body->mesh(), result, "one crack");
    EXPECT_TRUE(s.junctions.empty());
    EXPECT_EQ(result.fragments.count, 2);
  }
}

}  // namespace
}  // namespace fissure
