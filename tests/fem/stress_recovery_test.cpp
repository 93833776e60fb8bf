#include "fissure/base/error.hpp"
#include "fissure/fem/stress_recovery.hpp"

#include "fem_test_meshes.hpp"

#include <gtest/gtest.h>

namespace fissure {
namespace {

// A constant stress is reproduced exactly by both methods (their weights sum to 1 per node; the
// patch fit's to round-off of a 4 × 4 solve, hence 1e-9 rather than 1e-15).
TEST(StressRecovery, ConstantFieldIsExact) {
  const auto mesh = test::perturbed_box(4, 0.2, 3);
  Eigen::Matrix<double, 1, 6> sigma;
  sigma << 1e6, -2e6, 3e5, 4e5, -5e5, 6e5;
  const StressField tets = sigma.replicate(mesh->tet_count(), 1);
  for (RecoveryMethod method : {RecoveryMethod::NodalAverage, RecoveryMethod::PatchFit}) {
    const StressRecovery recovery(*mesh, method);
    EXPECT_EQ(recovery.fallback_nodes(), 0);
    const StressField nodal = recovery.nodal(tets);
    const StressField smoothed = recovery.smoothed_tets(tets);
    EXPECT_LT((nodal.rowwise() - sigma).cwiseAbs().maxCoeff(), 1e-9 * sigma.norm());
    EXPECT_LT((smoothed.rowwise() - sigma).cwiseAbs().maxCoeff(), 1e-9 * sigma.norm());
  }
}

// A stress field linear in position, sampled at the tet centroids, is recovered exactly at every
// node by the patch fit, surface and corner nodes included (round-off of a 4 × 4 solve on
// scaled offsets: 1e-9 of the field's magnitude). Nodal averaging is exact only where a node's
// tets surround it symmetrically, and is not on the surface.
TEST(StressRecovery, PatchRecoveryReproducesALinearField) {
  const auto mesh = test::perturbed_box(5, 0.2, 7);
  Eigen::Matrix<double, 6, 3> slope;
  slope.setRandom();
  slope *= 1e6;
  Eigen::Matrix<double, 6, 1> offset;
  offset.setRandom();
  offset *= 1e6;
  auto field = [&](const Eigen::Vector3d& x) -> Eigen::Matrix<double, 6, 1> { return offset + slope * x; };
  StressField tets(mesh->tet_count(), 6);
  for (int t = 0; t < mesh->tet_count(); ++t) tets.row(t) = field(mesh->centroid(t)).transpose();
  const StressField recovered = StressRecovery(*mesh, RecoveryMethod::PatchFit).nodal(tets);
  const StressField averaged = StressRecovery(*mesh, RecoveryMethod::NodalAverage).nodal(tets);
  double patch_worst = 0.0, average_worst = 0.0;
  for (int v = 0; v < mesh->node_count(); ++v) {
    const Eigen::Matrix<double, 6, 1> exact = field(mesh->nodes().row(v).transpose());
    patch_worst = std::max(patch_worst, (recovered.row(v).transpose() - exact).norm());
    average_worst = std::max(average_worst, (averaged.row(v).transpose() - exact).norm());
  }
  EXPECT_LT(patch_worst, 1e-9 * 1e6 * 10);
  EXPECT_GT(average_worst, 1e3 * patch_worst);  // averaging really is biased on the surface
}

// Two tets sharing a face: the shared nodes take the volume-weighted mean, the others their one
// tet's value; every nodal value lies within the range of the tets around it.
TEST(StressRecovery, VolumeWeightedMeanByHand) {
  Eigen::MatrixX3d nodes(5, 3);
  nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -3;  // tet 0 above z = 0 (V = 1/6), tet 1 below (V = 3/6)
  Eigen::MatrixX4i tets(2, 4);
  tets << 0, 1, 2, 3, 0, 2, 1, 4;
  const TetMesh mesh(nodes, tets, "two tets");
  ASSERT_NEAR(mesh.volumes()[0], 1.0 / 6.0, 1e-15);
  ASSERT_NEAR(mesh.volumes()[1], 3.0 / 6.0, 1e-15);
  StressField s(2, 6);
  s.row(0) << 4, 0, 0, 0, 0, 8;
  s.row(1) << 0, 4, 0, 0, 0, -8;
  const StressField nodal = StressRecovery(mesh, RecoveryMethod::NodalAverage).nodal(s);
  for (int v : {0, 1, 2}) {
    EXPECT_NEAR(nodal(v, 0), 1.0, 1e-15);   // (1/6·4 + 3/6·0) / (4/6)
    EXPECT_NEAR(nodal(v, 1), 3.0, 1e-15);
    EXPECT_NEAR(nodal(v, 5), -4.0, 1e-15);
  }
  EXPECT_EQ(StressField(nodal.row(3)), StressField(s.row(0)));
  EXPECT_EQ(StressField(nodal.row(4)), StressField(s.row(1)));
}

// Pure bending u = κ(xz, 0, −x²/2): exact stress D·(κz, 0, 0, 0, 0, 0), linear through the
// thickness. Constant-strain tets see it only through the linear interpolant of a quadratic
// field, whose gradient errs by O(h) and scatters with each tet's shape. On a perturbed plate two
// elements thick (the tile's situation), over the tets off the sides, the RMS error of the raw
// stress is 75 %; nodal averaging halves it (34 %: surface nodes are pulled towards the
// mid-plane), the two-ring patch fit brings it to 19 %. Each bound leaves ≈ 10 % over the
// measured value; the mesh is seeded, so the figures move only with round-off.
TEST(StressRecovery, SmoothingReducesBendingScatter) {
  // A plate 1 × 1 × 0.25 of 8 × 8 × 2 cells, interior nodes moved by up to 20 % of a cell.
  const TetMesh box = make_structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 1.0, 0.25), 8, 8, 2);
  Eigen::MatrixX3d nodes = box.nodes();
  Rng rng(11);
  const Eigen::Vector3d cell(0.125, 0.125, 0.125);
  for (int v = 0; v < nodes.rows(); ++v) {
    const Eigen::Vector3d p = nodes.row(v);
    if ((p.array() < 1e-9).any() || p.x() > 1 - 1e-9 || p.y() > 1 - 1e-9 || p.z() > 0.25 - 1e-9) continue;
    for (int i = 0; i < 3; ++i) nodes(v, i) += 0.2 * cell[i] * rng.uniform(-1.0, 1.0);
  }
  const TetMesh mesh(nodes, box.tets(), "plate");
  const ElasticMaterial material = test::concrete();
  const TetGradients gradients = compute_tet_gradients(mesh);
  const double kappa = 1e-3;
  Eigen::VectorXd u(3 * mesh.node_count());
  for (int v = 0; v < mesh.node_count(); ++v) {
    const double x = nodes(v, 0), z = nodes(v, 2) - 0.125;
    u.segment<3>(3 * v) << kappa * x * z, 0.0, -0.5 * kappa * x * x;
  }
  const StressField raw = compute_stress(mesh, gradients, material, u);
  const StressField averaged = StressRecovery(mesh, RecoveryMethod::NodalAverage).smoothed_tets(raw);
  const StressRecovery patch(mesh, RecoveryMethod::PatchFit);
  EXPECT_EQ(patch.fallback_nodes(), 0);
  const StressField patched = patch.smoothed_tets(raw);
  const Eigen::Matrix<double, 6, 6> d = material.elasticity_matrix();
  double raw_error = 0.0, averaged_error = 0.0, patched_error = 0.0, norm = 0.0;
  for (int t = 0; t < mesh.tet_count(); ++t) {
    bool off_sides = true;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = nodes.row(mesh.tets()(t, k));
      off_sides = off_sides && p.x() > 1e-9 && p.y() > 1e-9 && p.x() < 1 - 1e-9 && p.y() < 1 - 1e-9;
    }
    if (!off_sides) continue;
    Eigen::Matrix<double, 6, 1> strain = Eigen::Matrix<double, 6, 1>::Zero();
    strain[0] = kappa * (mesh.centroid(t).z() - 0.125);
    const Eigen::Matrix<double, 6, 1> exact = d * strain;
    raw_error += (raw.row(t).transpose() - exact).squaredNorm();
    averaged_error += (averaged.row(t).transpose() - exact).squaredNorm();
    patched_error += (patched.row(t).transpose() - exact).squaredNorm();
    norm += exact.squaredNorm();
  }
  ASSERT_GT(norm, 0.0);
  raw_error = std::sqrt(raw_error / norm);
  averaged_error = std::sqrt(averaged_error / norm);
  patched_error = std::sqrt(patched_error / norm);
  const std::string figures = "raw " + std::to_string(raw_error) + ", averaged " + std::to_string(averaged_error) +
                              ", patch " + std::to_string(patched_error);
  EXPECT_GT(raw_error, 0.6) << figures;  // the scatter is real
  EXPECT_LT(averaged_error, 0.375) << figures;  // measured 0.340
  EXPECT_LT(patched_error, 0.21) << figures;    // measured 0.193
}

// The weights depend on shape only: scaling the mesh by 1e-3 or 1e3 (the stability sweep's
// scales) changes them by round-off (offsets are scaled by the patch radius, volumes normalised
// by the patch volume), and a mesh with a near-flat sliver gives finite weights.
TEST(StressRecovery, WeightsAreScaleInvariantAndFinite) {
  const auto mesh = test::perturbed_box(4, 0.2, 5);
  const StressRecovery unit(*mesh);
  for (double scale : {1e-3, 1e3}) {
    const TetMesh scaled(mesh->nodes() * scale, mesh->tets(), "scaled");
    const StressRecovery recovery(scaled);
    ASSERT_EQ(recovery.weights().nonZeros(), unit.weights().nonZeros());
    const Eigen::SparseMatrix<double, Eigen::RowMajor> difference = recovery.weights() - unit.weights();
    double worst = 0.0;
    for (int k = 0; k < difference.outerSize(); ++k)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(difference, k); it; ++it)
        worst = std::max(worst, std::abs(it.value()));
    EXPECT_LT(worst, 1e-10) << "scale " << scale;
  }
  // A sliver: lift one interior node of a 2 × 2 × 2 box almost into the plane of its neighbours.
  Eigen::MatrixX3d nodes = make_structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 2, 2, 2).nodes();
  const TetMesh box = make_structured_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 2, 2, 2);
  for (int v = 0; v < nodes.rows(); ++v)
    if ((nodes.row(v).array() - 0.5).abs().maxCoeff() < 1e-12) nodes(v, 2) = 0.5 + 0.49;
  const TetMesh sliver(nodes, box.tets(), "sliver");
  const StressRecovery recovery(sliver);
  for (int k = 0; k < recovery.weights().nonZeros(); ++k) ASSERT_TRUE(std::isfinite(recovery.weights().valuePtr()[k]));
}

TEST(StressRecovery, WrongSizesAreRefused) {
  const auto mesh = test::box_mesh({0, 0, 0}, {1, 1, 1}, 1, 1, 1);
  const StressRecovery recovery(*mesh);
  EXPECT_THROW(recovery.nodal(StressField::Zero(mesh->tet_count() + 1, 6)), InvalidInput);
  EXPECT_THROW(recovery.smoothed_tets(StressField::Zero(mesh->tet_count() - 1, 6)), InvalidInput);
}

}  // namespace
}  // namespace fissure
