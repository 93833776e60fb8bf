#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/fem/modal_basis.hpp"
#include "fissure/fem/sparse_cholesky.hpp"
#include "fissure/fem/stress.hpp"
#include "fissure/fem/supports.hpp"

#include "fem_test_meshes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <numbers>

namespace fissure {
namespace {

std::vector<int> fixed(const TetMesh& mesh, const char* spec) {
  return resolve_supports(mesh, {parse_support(spec)});
}

// Generalised eigen-residual ‖Kφ − λMφ‖ / ‖Kφ‖ and M-orthonormality of a basis.
void expect_valid_eigenpairs(const ElasticBody& body, const ModalBasis& basis, const std::vector<int>& fixed_dofs) {
  const DofMap dofs(body.stiffness().rows(), fixed_dofs);
  const Eigen::MatrixXd& phi = basis.modes();
  Eigen::MatrixXd m_phi(phi.rows(), phi.cols());
  for (Eigen::Index j = 0; j < phi.cols(); ++j) {
    m_phi.col(j) = body.mass_times(basis.mass(), phi.col(j));
    const Eigen::VectorXd k_phi = body.stiffness() * phi.col(j);
    // Residual on the free dofs (fixed dofs carry reactions). Spectra's tolerance 1e-10 on the
    // Ritz values bounds the vector residual at ~1e-5 relative; 1e-6 is what converged pairs reach.
    const Eigen::VectorXd r = dofs.restrict_vector(k_phi - basis.eigenvalues()[j] * m_phi.col(j));
    EXPECT_LT(r.norm(), 1e-6 * dofs.restrict_vector(k_phi).norm()) << "mode " << j;
    for (int d : fixed_dofs) ASSERT_EQ(phi(d, j), 0.0);
  }
  const Eigen::MatrixXd gram = phi.transpose() * m_phi;
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff(), 1e-9);
  for (Eigen::Index j = 1; j < basis.eigenvalues().size(); ++j) {
    EXPECT_GE(basis.eigenvalues()[j], basis.eigenvalues()[j - 1]);
  }
}

// Clamped-free beam 1 × 0.1 × 0.1 m (fem-pitfalls.md §1.3): Euler–Bernoulli gives
// f1 = 1.8751²/(2πL²)·√(EI/ρA) = 57.113 Hz; the converged 3D value (C3D10) is 56.944 Hz.
// Linear tets are too stiff, so f1 falls towards it as the mesh is refined.
TEST(ModalBasis, ClampedBeamFirstFrequencyConverges) {
  const ElasticMaterial m{3.0e10, 0.3, 2400};
  const double a = 0.1, length = 1.0;
  const double euler_bernoulli = 1.875104 * 1.875104 / (2 * std::numbers::pi * length * length) *
                                 std::sqrt(m.youngs_modulus * (a * a * a * a / 12.0) / (m.density * a * a));
  ASSERT_NEAR(euler_bernoulli, 57.113, 0.01);
  const double converged_3d = 56.944;
  const int across[3] = {2, 4, 8};
  double error[3], split[3];
  for (int k = 0; k < 3; ++k) {
    const int n = across[k];
    auto mesh = test::box_mesh({0, 0, 0}, {length, a, a}, 10 * n, n, n);
    auto body = std::make_shared<const ElasticBody>(mesh, m);
    const auto supports = fixed(*mesh, "xmin");
    ModalOptions options;
    options.mode_count = 4;
    const ModalBasis lumped = ModalBasis::compute(body, supports, options);
    if (n <= 4) expect_valid_eigenpairs(*body, lumped, supports);
    const double f1 = lumped.frequencies_hz()[0];
    // The square section bends alike in y and z; the Kuhn split is not symmetric between the
    // two, so the pair agrees only to the discretisation error, which must shrink.
    split[k] = (lumped.frequencies_hz()[1] - f1) / f1;
    error[k] = (f1 - converged_3d) / converged_3d;
    std::printf("clamped beam, %d across (%d tets): f1 = %.3f Hz lumped, %+.2f %% vs 3D, %+.2f %% vs Euler-Bernoulli\n",
                n, mesh->tet_count(), f1, 100 * error[k], 100 * (f1 - euler_bernoulli) / euler_bernoulli);
    EXPECT_GT(error[k], 0.0);
    if (n == 4) {
      // Consistent mass is a Rayleigh–Ritz discretisation: its frequencies bound the continuum
      // ones from above (56.944 Hz, itself within 0.1 % of the true 3D value).
      options.mass = MassKind::Consistent;
      const ModalBasis consistent = ModalBasis::compute(body, supports, options);
      EXPECT_GT(consistent.frequencies_hz()[0], converged_3d * 0.999);
      EXPECT_GT(consistent.frequencies_hz()[0], f1);  // lumped is lower (fem-pitfalls §2.3)
    }
  }
  EXPECT_GT(error[0], error[1]);
  EXPECT_GT(error[1], error[2]);
  EXPECT_GT(split[0], split[1]);
  EXPECT_GT(split[1], split[2]);
  EXPECT_LT(split[2], 0.05);
  const double order = std::log2(error[1] / error[2]);
  std::printf("measured order of f1: %.2f (4 -> 8 across)\n", order);
  // fem-pitfalls.md §1.3 measures h^1.9 on gmsh meshes.
  EXPECT_GT(order, 1.2);
  EXPECT_LT(order, 2.6);
  EXPECT_LT(error[2], 0.10);  // 8 across: +2.7 % on gmsh meshes
}

// An independent count: the dense generalised eigenproblem of a small free body has exactly six
// eigenvalues near zero, and ModalBasis finds the same flexible spectrum.
TEST(ModalBasis, DenseSpectrumOfAFreeBodyHasSixZeros) {
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.6, 0.3}, 3, 2, 1);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  const Eigen::MatrixXd k(body->stiffness());
  const Eigen::MatrixXd m = body->lumped_mass().asDiagonal();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(k, m);
  const Eigen::VectorXd lambda = dense.eigenvalues();
  int zeros = 0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) zeros += std::abs(lambda[i]) < 1e-6 * lambda[6];
  EXPECT_EQ(zeros, 6);
  ModalOptions options;
  options.mode_count = 8;
  const ModalBasis basis = ModalBasis::compute(body, {}, options);
  for (int j = 0; j < 8; ++j) EXPECT_NEAR(basis.eigenvalues()[j], lambda[6 + j], 1e-9 * lambda[6 + j]) << j;
}

TEST(ModalBasis, FreeBodyHasExactlySixRigidModes) {
  auto mesh = test::box_mesh({-0.5, -0.5, 0}, {1.0, 1.0, 0.05}, 16, 16, 2);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  ModalOptions options;
  options.mode_count = 10;
  const ModalBasis basis = ModalBasis::compute(body, {}, options);
  ASSERT_TRUE(basis.free_body());
  ASSERT_EQ(basis.rigid_eigenvalues().size(), 6);
  const double first_flexible = basis.eigenvalues()[0];
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(basis.rigid_eigenvalues()[i]), 1e-6 * first_flexible);
  EXPECT_GT(first_flexible, 0.0);
  expect_valid_eigenpairs(*body, basis, {});
  // Flexible modes carry no rigid motion.
  const Eigen::MatrixXd& r = basis.rigid_modes();
  for (int j = 0; j < basis.mode_count(); ++j) {
    EXPECT_LT((r.transpose() * body->mass_times(MassKind::Lumped, basis.modes().col(j))).norm(), 1e-10);
  }
  std::printf("free tile (%d tets): f7..f9 = %.1f, %.1f, %.1f Hz\n", mesh->tet_count(), basis.frequencies_hz()[0],
              basis.frequencies_hz()[1], basis.frequencies_hz()[2]);
  // Kirchhoff plate theory gives 114.85 Hz for the first free mode of this tile; two tet layers
  // through 5 cm are far too stiff in bending (+99 % at 5K tets, fem-pitfalls.md §1.4).
  EXPECT_GT(basis.frequencies_hz()[0], 114.85);
  EXPECT_LT(basis.frequencies_hz()[0], 3 * 114.85);
}

TEST(ModalBasis, TwoFreeComponentsHaveTwelveRigidModes) {
  const TetMesh a = make_structured_box({0, 0, 0}, {1, 0.3, 0.2}, 6, 2, 2);
  const TetMesh b = make_structured_box({2, 0, 0}, {1, 0.3, 0.2}, 6, 2, 2);
  Eigen::MatrixX3d nodes(a.node_count() + b.node_count(), 3);
  nodes << a.nodes(), b.nodes();
  Eigen::MatrixX4i tets(a.tet_count() + b.tet_count(), 4);
  tets << a.tets(), (b.tets().array() + a.node_count()).matrix();
  auto body = std::make_shared<const ElasticBody>(std::make_shared<const TetMesh>(nodes, tets), test::concrete());
  ModalOptions options;
  options.mode_count = 4;
  const ModalBasis basis = ModalBasis::compute(body, {}, options);
  EXPECT_EQ(basis.rigid_eigenvalues().size(), 12);
  EXPECT_EQ(basis.rigid_modes().cols(), 12);
  // The two identical bars give every flexible frequency twice.
  EXPECT_NEAR(basis.eigenvalues()[1], basis.eigenvalues()[0], 1e-8 * basis.eigenvalues()[0]);
  EXPECT_NEAR(basis.eigenvalues()[3], basis.eigenvalues()[2], 1e-8 * basis.eigenvalues()[2]);
}

// The modal static solve reproduces the direct solve as m grows: with all modes it is exact,
// and with m modes the energy error is monotone (the modal sum is a K-orthogonal projection).
TEST(ModalBasis, ModalSolveApproachesDirectSolve) {
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.2, 0.1}, 10, 2, 1);  // 120 tets, 198 dofs
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  const auto supports = fixed(*mesh, "xmin");
  const DofMap dofs(body->stiffness().rows(), supports);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(body->stiffness().rows());
  for (int v = 0; v < mesh->node_count(); ++v) f[3 * v + 2] = mesh->nodes()(v, 0) > 0.95 ? -100.0 : 0.0;
  SparseCholesky chol;
  chol.factorize(dofs.restrict_matrix(body->stiffness()));
  const Eigen::VectorXd exact = dofs.expand_vector(chol.solve(dofs.restrict_vector(f)));
  double previous = INFINITY;
  for (int m : {5, 20, 80, dofs.free_count() - 1}) {
    ModalOptions options;
    options.mode_count = m;
    const ModalBasis basis = ModalBasis::compute(body, supports, options);
    const Eigen::VectorXd u = basis.static_displacement(f);
    const Eigen::VectorXd e = u - exact;
    const double energy_error = std::sqrt(e.dot(body->stiffness() * e) / exact.dot(body->stiffness() * exact));
    EXPECT_LT(energy_error, previous) << "m = " << m;
    previous = energy_error;
  }
  // m = n − 1 leaves out only the highest mode, whose share of a smooth load is tiny.
  EXPECT_LT(previous, 1e-3);
}

// The float copy of Φ changes the answer by round-off only. Each u_i sums m = 30 products of
// float-rounded terms: worst case |δu_i| ≈ (m + 2)·2⁻²⁴·Σ_k |Φ_ik q_k| ≈ 2e-6 of the terms,
// typically √m·2⁻²⁴ ≈ 3e-7 (measured 1.1e-7); 1e-5 allows the worst case with a factor 5 of
// cancellation. Stress is a difference of nodal values: a cantilever's strain is ≈ t·h/L² of
// u/h (t = 0.1 thick, h = 0.05 elements, L = 1), so round-off in u grows ≈ 200× in stress:
// 200 × 3e-7 = 6e-5 expected (measured 2.7e-5), tolerance 1e-4.
TEST(ModalBasis, SinglePrecisionSolveMatchesDouble) {
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.2, 0.1}, 10, 2, 2);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  const auto supports = fixed(*mesh, "xmin");
  Eigen::VectorXd f = Eigen::VectorXd::Zero(body->stiffness().rows());
  for (int v = 0; v < mesh->node_count(); ++v) f[3 * v + 2] = mesh->nodes()(v, 0) > 0.95 ? -100.0 : 0.0;
  ModalOptions options;
  options.mode_count = 30;
  const ModalBasis basis = ModalBasis::compute(body, supports, options);
  const Eigen::VectorXd u = basis.static_displacement(f, ModalPrecision::Double);
  const Eigen::VectorXd u_single = basis.static_displacement(f, ModalPrecision::Single);
  ASSERT_TRUE(u_single.allFinite());
  const double u_error = (u_single - u).norm() / u.norm();
  EXPECT_LT(u_error, 1e-5);
  EXPECT_GT(u_error, 0.0);  // it really ran in float: a bitwise-equal answer would mean it did not
  const StressField s = compute_stress(*body, u);
  const StressField s_single = compute_stress(*body, u_single);
  EXPECT_LT((s_single - s).norm() / s.norm(), 1e-4);
}

TEST(ModalBasis, CacheSavesReloadsAndRejectsStaleFiles) {
  const auto dir = test::fresh_temp_dir("modal-cache");
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.2, 0.1}, 10, 2, 2);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  const auto supports = fixed(*mesh, "xmin");
  ModalOptions options;
  options.mode_count = 8;
  bool loaded = true;
  const ModalBasis first = cached_modal_basis(body, supports, options, dir, &loaded);
  EXPECT_FALSE(loaded);
  const ModalBasis second = cached_modal_basis(body, supports, options, dir, &loaded);
  EXPECT_TRUE(loaded);
  EXPECT_TRUE(first.modes() == second.modes());
  EXPECT_TRUE(first.eigenvalues() == second.eigenvalues());
  const Eigen::VectorXd f = Eigen::VectorXd::Ones(first.modes().rows());
  EXPECT_TRUE(first.static_displacement(f, ModalPrecision::Single) ==
              second.static_displacement(f, ModalPrecision::Single));  // the float copy is rebuilt on load

  // Different material, supports or mode count → different key.
  const Hash128 key = ModalBasis::cache_key(*body, supports, options);
  auto stiffer = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{4e10, 0.2, 2400});
  EXPECT_FALSE(ModalBasis::cache_key(*stiffer, supports, options) == key);
  EXPECT_FALSE(ModalBasis::cache_key(*body, fixed(*mesh, "xmax"), options) == key);
  ModalOptions more = options;
  more.mode_count = 9;
  EXPECT_FALSE(ModalBasis::cache_key(*body, supports, more) == key);

  // A truncated cache file is detected and recomputed.
  const auto file = dir / ("modes-" + key.hex() + ".bin");
  ASSERT_TRUE(std::filesystem::exists(file));
  const std::string bytes = read_file(file);
  write_file_atomically(file, bytes.substr(0, bytes.size() / 2));
  EXPECT_THROW(ModalBasis::load(file, key), IoError);
  const ModalBasis third = cached_modal_basis(body, supports, options, dir, &loaded);
  EXPECT_FALSE(loaded);
  EXPECT_TRUE(third.modes() == first.modes());
  EXPECT_THROW(ModalBasis::load(file, ModalBasis::cache_key(*stiffer, supports, options)), IoError);

  // A file of the right size and key whose last mode value is a NaN is refused, not solved with.
  std::string damaged = read_file(file);
  const double nan = std::nan("");
  damaged.replace(damaged.size() - sizeof(double), sizeof(double), reinterpret_cast<const char*>(&nan), sizeof(double));
  write_file_atomically(file, damaged);
  EXPECT_THROW(ModalBasis::load(file, key), IoError);
}

TEST(ModalBasis, BadRequestsAreRefused) {
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.2, 0.1}, 2, 1, 1);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  ModalOptions options;
  options.mode_count = 0;
  EXPECT_THROW(ModalBasis::compute(body, {}, options), InvalidInput);
  options.mode_count = 500;
  EXPECT_THROW(ModalBasis::compute(body, fixed(*mesh, "xmin"), options), InvalidInput);
  options.mode_count = 3;
  EXPECT_THROW(ModalBasis::compute(body, fixed(*mesh, "box:0,0,0,0,0,0"), options), InvalidInput);  // one node
}

}  // namespace
}  // namespace fissure
