// The relaxation of one element (Eqs. 3–4) with the tensile-only clamp: relaxation never turns
// tension into compression along the direction it acts on, leaves compression alone, and never
// raises λ_max (which the event queue's lazy re-check relies on: simulation.hpp).
#include "fissure/base/rng.hpp"
#include "fissure/fem/stress.hpp"
#include "fissure/fracture/simulation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>

namespace fissure {
namespace {

using Voigt = Eigen::Matrix<double, 6, 1>;

double along(const Voigt& s, const Eigen::Vector3d& d) { return d.dot(voigt_to_tensor(s) * d); }

Eigen::Vector3d eigenvalues(const Voigt& s) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(voigt_to_tensor(s), Eigen::EigenvaluesOnly).eigenvalues();
}

// Round-off of one Voigt update and one 3 × 3 eigen-solve, relative to the stress's size: each
// is a handful of operations at 1e-16, so 1e-12 is generous and still 1e-6 of any relaxation
// tested here (amounts ≥ 1e-6 of |σ|).
double slack(const Voigt& s) { return 1e-12 * (1.0 + s.cwiseAbs().maxCoeff()); }

Voigt random_stress(Rng& rng, double scale) {
  Voigt s;
  for (int i = 0; i < 6; ++i) s(i) = scale * rng.uniform(-1.0, 1.0);
  return s;
}

Eigen::Vector3d random_direction(Rng& rng) {
  Eigen::Vector3d d;
  do {
    d = Eigen::Vector3d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
  } while (d.norm() < 0.1);
  return d.normalized();
}

TEST(RelaxElementStress, DirectionalRemovesTensionAlongDUpToZero) {
  // σ_xx = 5 MPa tension along d = x; a relaxation of 8 MPa removes exactly the 5 (not 8).
  Voigt s;
  s << 5e6, 2e6, 1e6, 0, 0, 0;
  const Voigt r = relax_element_stress(s, 8e6, true, Eigen::Vector3d::UnitX());
  EXPECT_EQ(r(0), 0.0);
  EXPECT_EQ(r(1), 2e6);  // directions orthogonal to d keep their stress
  EXPECT_EQ(r(2), 1e6);
  // A smaller relaxation removes its own amount.
  EXPECT_DOUBLE_EQ(relax_element_stress(s, 3e6, true, Eigen::Vector3d::UnitX())(0), 2e6);
}

TEST(RelaxElementStress, DirectionalLeavesCompressionAlongDUntouched) {
  Voigt s;
  s << -4e6, 3e6, 0, 1e6, 2e6, 5e5;
  EXPECT_EQ(relax_element_stress(s, 1e7, true, Eigen::Vector3d::UnitX()), s);
}

TEST(RelaxElementStress, IsotropicRemovesAtMostTheLargestTension) {
  Voigt s;
  s << 5e6, 2e6, -1e6, 0, 0, 0;
  const Voigt r = relax_element_stress(s, 8e6, false, Eigen::Vector3d::Zero());
  EXPECT_NEAR(max_principal_stress(r), 0.0, slack(s));
  // Every direction loses the same 5 MPa (Eq. 4), so σ_yy goes from 2 MPa tension to 3 MPa
  // compression: the clamp guards λ_max, the stress that opens cracks, not the lesser principal
  // stresses (reading b of paper-gaps §4 applied to Eq. 4's single amount).
  EXPECT_DOUBLE_EQ(r(1), -3e6);
  Voigt c;
  c << -5e6, -2e6, -1e6, 1e5, 0, 0;  // all compressive: untouched
  EXPECT_EQ(relax_element_stress(c, 8e6, false, Eigen::Vector3d::Zero()), c);
}

// Random tensors, directions and amounts, from far below to far above the stress: the clamp
// holds for every one, and no principal stress rises (σ less a positive semi-definite tensor).
TEST(RelaxElementStress, NeverTurnsTensionIntoCompressionNorRaisesAPrincipalStress) {
  Rng rng(2024);
  for (int i = 0; i < 20000; ++i) {
    const Voigt s = random_stress(rng, 1e7);
    const Eigen::Vector3d d = random_direction(rng);
    const double amount = std::pow(10.0, rng.uniform(0.0, 9.0));  // 1 Pa … 1 GPa
    for (bool directional : {true, false}) {
      const Voigt r = relax_element_stress(s, amount, directional, d);
      ASSERT_TRUE(r.allFinite());
      const Eigen::Vector3d before = eigenvalues(s), after = eigenvalues(r);
      for (int k = 0; k < 3; ++k) ASSERT_LE(after(k), before(k) + slack(s)) << i << (directional ? " Eq. 3" : " Eq. 4");
      if (directional) {
        const double s_d = along(s, d), r_d = along(r, d);
        if (s_d > 0.0) {
          ASSERT_GE(r_d, -slack(s)) << i;  // tension along d ends at ≥ 0 …
          ASSERT_NEAR(r_d, std::max(0.0, s_d - amount), slack(s)) << i;  // … by exactly min(amount, s_d)
        } else {
          ASSERT_EQ(r, s) << i;  // compression along d: untouched
        }
      } else {
        const double lambda = before(2);
        if (lambda > 0.0) {
          ASSERT_GE(after(2), -slack(s)) << i;
          ASSERT_NEAR(after(2), std::max(0.0, lambda - amount), slack(s)) << i;
        } else {
          ASSERT_EQ(r, s) << i;
        }
      }
    }
  }
}

// The kernel at the smallest radius the parameter table admits (the next double above 0): r² and
// r⁶ underflow there, so the kernel must not be computed from them (0/0 at d = 0 would be NaN and
// reach every relaxed stress).
TEST(RelaxationKernel, FiniteAtTheSmallestRadius) {
  const double r = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(relaxation_kernel(0.0, r), 1.0);
  EXPECT_EQ(relaxation_kernel(r, r), 0.0);
  const double tiny = 1e-300;  // r² underflows to 0 here too
  EXPECT_EQ(relaxation_kernel(0.0, tiny), 1.0);
  EXPECT_DOUBLE_EQ(relaxation_kernel(0.5 * tiny, tiny), 0.421875);  // (1 − 1/4)³
}

TEST(RelaxElementStress, ZeroAmountChangesNothing) {
  Rng rng(3);
  for (int i = 0; i < 100; ++i) {
    const Voigt s = random_stress(rng, 1e6);
    EXPECT_EQ(relax_element_stress(s, 0.0, true, random_direction(rng)), s);
    EXPECT_EQ(relax_element_stress(s, 0.0, false, Eigen::Vector3d::Zero()), s);
  }
}

}  // namespace
}  // namespace fissure
