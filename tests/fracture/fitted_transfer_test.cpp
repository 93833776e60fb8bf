// A fitted material moved to another body (fitted_transfer.hpp): the reference stress follows
// linear elasticity's scaling law exactly, the fitted load keeps the fit's stress on a similar
// body of another size, and the length map scales lengths only. The statistics themselves on
// 0.3× and 3× tiles are checked end to end in tests/cli/fit_cli_test.cpp.

#include "fissure/base/error.hpp"
#include "fissure/fracture/fitted_transfer.hpp"

#include "fracture_test_bodies.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace fissure {
namespace {

std::shared_ptr<const TetMesh> scaled(const TetMesh& mesh, double s) {
  return std::make_shared<const TetMesh>(Eigen::MatrixX3d(mesh.nodes() * s), mesh.tets());
}

double max_abs(const StressField& s) { return s.cwiseAbs().maxCoeff(); }

TEST(FittedTransfer, ReferenceStressScalesAsForceOverAreaOnASimilarBody) {
  // Geometry × s at a fixed force: every stress × 1/s² (equilibrium over areas × s²), the same
  // mesh so no discretisation differs. The factor's round-off is ~1e-12 relative; 1e-9 leaves
  // three decades and still catches any length that does not scale (a patch radius in metres).
  const auto small = test::plate_mesh({0.5, 0.4, 0.02}, 16, 12, 2);
  const FractureParams params;
  const PreparedBody a(small, params.elastic(), FractureScenario{});
  const double ref = reference_stress_per_newton(a);
  EXPECT_GT(ref, 0.0);
  for (double s : {0.3, 3.0}) {
    const PreparedBody b(scaled(*small, s), params.elastic(), FractureScenario{});
    EXPECT_NEAR(reference_stress_per_newton(b) * s * s / ref, 1.0, 1e-9) << "s = " << s;
  }
}

TEST(FittedTransfer, TheFittedLoadIsLmgOnTheFitBodyAndKeepsItsStressOnASimilarOne) {
  const auto fit_mesh = test::plate_mesh({0.5, 0.4, 0.02}, 16, 12, 2);
  FractureParams params;
  params.load_factor = 7.0;
  const PreparedBody fit_body(fit_mesh, params.elastic(), FractureScenario{});
  const double mg = fit_body.fracture_body().mass(params.density) * kStandardGravity;
  MaterialFit fit;
  fit.body_width = 0.5;
  fit.body_height = 0.4;
  fit.load_reference_stress = reference_stress_per_newton(fit_body) * mg;
  // On the fit body: l·m·g, to round-off.
  EXPECT_NEAR(fitted_load_force(fit, params, fit_body) / (params.load_factor * mg), 1.0, 1e-12);
  // On the body three times larger in every direction, the fitted force gives the fit's stress
  // field, point for point (same mesh scaled): its peak equals the fit body's.
  const PreparedBody big(scaled(*fit_mesh, 3.0), params.elastic(), FractureScenario{});
  const double force = fitted_load_force(fit, params, big);
  EXPECT_NEAR(force / (params.load_factor * mg * 9.0), 1.0, 1e-9) << "F' = l·σ_ref,fit/σ_ref' = l·m·g·s²";
  const LoadSpec fit_patch = default_load(*fit_mesh, Eigen::Vector3d::UnitZ(), params.load_factor * mg);
  const LoadSpec big_patch = default_load(big.mesh(), Eigen::Vector3d::UnitZ(), force);
  const double fit_peak = max_abs(fit_body.stress_of_forces(assemble_load(*fit_mesh, fit_patch)));
  const double big_peak = max_abs(big.stress_of_forces(assemble_load(big.mesh(), big_patch)));
  EXPECT_NEAR(big_peak / fit_peak, 1.0, 1e-9);
  // l·m·g on the big body (27× the mass) would carry 3× the stress: what the transfer prevents.
  EXPECT_NEAR(params.load_factor * big.fracture_body().mass(params.density) * kStandardGravity / force, 3.0, 1e-9);
  // A fit from before the reference stress: l·m·g of the body itself.
  fit.load_reference_stress = 0.0;
  EXPECT_DOUBLE_EQ(fitted_load_force(fit, params, big),
                   params.load_factor * params.density * big.mesh().total_volume() * kStandardGravity);
}

TEST(FittedTransfer, TheLengthScaleFollowsTheVisibleFace) {
  MaterialFit fit;
  fit.body_width = 1.0;
  fit.body_height = 0.8;
  EXPECT_EQ(fitted_length_scale(fit, 0.8 * (1.0 + 1e-12)), 1.0) << "the fit body meshed again is the fit body";
  EXPECT_NEAR(fitted_length_scale(fit, 0.8 * 0.09), 0.3, 1e-15);
  EXPECT_NEAR(fitted_length_scale(fit, 0.8 * 9.0), 3.0, 1e-15);
  EXPECT_THROW(fitted_length_scale(fit, 0.0), InvalidInput);
  EXPECT_THROW(fitted_length_scale(fit, std::nan("")), InvalidInput);
  fit.body_width = 0.0;
  EXPECT_THROW(fitted_length_scale(fit, 1.0), InvalidInput) << "a fit record without its body";
}

TEST(FittedTransfer, ScalingMovesLengthsAndNothingElse) {
  const FractureParams p;
  const FractureParams q = scale_lengths(p, 3.0);
  EXPECT_DOUBLE_EQ(q.relax_radius, 3.0 * p.relax_radius);
  EXPECT_DOUBLE_EQ(q.resistance_correlation, 3.0 * p.resistance_correlation);
  EXPECT_DOUBLE_EQ(q.fracture_toughness, std::sqrt(3.0) * p.fracture_toughness);
  for (std::size_t i = 0; i < p.noise.size(); ++i) {
    EXPECT_DOUBLE_EQ(q.noise[i].amplitude, 3.0 * p.noise[i].amplitude);
    EXPECT_DOUBLE_EQ(q.noise[i].frequency, p.noise[i].frequency / 3.0);
  }
  // Stresses against resistance, the age and l are relative already.
  for (std::size_t row = 0; row < fracture_parameter_table().size(); ++row) {
    const std::string name = fracture_parameter_table()[row].name;
    if (name == "relax_radius" || name == "resistance_correlation" || name == "fracture_toughness" ||
        name.rfind("noise_", 0) == 0) {
      continue;
    }
    EXPECT_EQ(parameter_value(q, row), parameter_value(p, row)) << name;
  }
  const FractureParams same = scale_lengths(p, 1.0);
  EXPECT_EQ(same.relax_radius, p.relax_radius);
  EXPECT_THROW(scale_lengths(p, 0.0), InvalidInput);
  EXPECT_THROW(scale_lengths(p, -2.0), InvalidInput);
}

}  // namespace
}  // namespace fissure
