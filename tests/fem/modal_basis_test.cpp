#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/fem/dof_map.hpp"
#include "fissure/fem/modal_basis.hpp"
#include "fissure/fem/rigid_modes.hpp"
#include "fissure/fem/sparse_cholesky.hpp"
#include "fissure/fem/stress.hpp"
#include "fissure/fem/supports.hpp"

#include "fem_test_meshes.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <Spectra/SymGEigsShiftSolver.h>

#include <chrono>
#include <cstring>
#include <cmath>
#include <mutex>
#include <numbers>
#include <string>
#include <utility>

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

// A free body with consistent mass: the shift −σM is subtracted inside K's pattern (consistent
// M couples the dofs of a tet's nodes, all of which K couples too), so this checks that in-place
// subtraction against the dense generalised eigensolve, to the same 1e-9 as the lumped case.
TEST(ModalBasis, FreeBodyWithConsistentMassMatchesTheDenseSpectrum) {
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.6, 0.3}, 3, 2, 1);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  const Eigen::MatrixXd k(body->stiffness());
  const Eigen::MatrixXd m(body->mass_matrix(MassKind::Consistent));
  const Eigen::VectorXd lambda = Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(k, m).eigenvalues();
  ModalOptions options;
  options.mode_count = 8;
  options.mass = MassKind::Consistent;
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
}

// The first free mode of the 1 × 1 × 0.05 m tile against Kirchhoff plate theory, 114.85 Hz
// (ω a² √(ρt/D) = 13.86 for a free square plate at ν = 0.2; the 3D/Mindlin correction at a/t = 20 is below
// 1 %). Two tet layers lock in bending, so f7 is far too high (+90 % at 16 × 16 cells), but it
// must converge to the right limit as the cells shrink: refined 16 → 24 → 32 in-plane, the
// errors must fall monotonically at a consistent rate, and the Richardson extrapolation with the
// observed order must land on Kirchhoff within 2 % (1 % for the plate model, 1 % for the
// remainder of the extrapolation). A wrong mass or stiffness converges to a wrong limit and
// fails; the old band [1×, 3×] of 114.85 Hz accepted either.
TEST(ModalBasis, FreePlateConvergesToKirchhoff) {
  const double kirchhoff = 114.85;
  double f[3];
  const int cells[3] = {16, 24, 32};
  for (int k = 0; k < 3; ++k) {
    auto mesh = test::box_mesh({-0.5, -0.5, 0}, {1.0, 1.0, 0.05}, cells[k], cells[k], 2);
    auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
    ModalOptions options;
    options.mode_count = 1;
    f[k] = ModalBasis::compute(body, {}, options).frequencies_hz()[0];
  }
  EXPECT_GT(f[0], f[1]);
  EXPECT_GT(f[1], f[2]);
  EXPECT_GT(f[2], kirchhoff);  // linear tets are too stiff
  // Observed order p from three meshes with ratios r1 = 24/16, r2 = 32/24: solve
  // (f0 − f1)/(f1 − f2) = (r1^p − 1)·r2^p / (r2^p − 1) for p by bisection.
  const double r1 = 1.5, r2 = 32.0 / 24.0, target = (f[0] - f[1]) / (f[1] - f[2]);
  auto ratio = [&](double p) { return (std::pow(r1, p) - 1.0) * std::pow(r2, p) / (std::pow(r2, p) - 1.0); };
  double lo = 0.2, hi = 4.0;
  for (int i = 0; i < 60; ++i) (ratio(0.5 * (lo + hi)) < target ? lo : hi) = 0.5 * (lo + hi);
  const double order = 0.5 * (lo + hi);
  const double extrapolated = f[2] - (f[1] - f[2]) / (std::pow(r2, order) - 1.0);
  std::printf("free plate f7: %.2f, %.2f, %.2f Hz (16, 24, 32 cells); order %.2f; extrapolated %.2f Hz, Kirchhoff %.2f Hz\n",
              f[0], f[1], f[2], order, extrapolated, kirchhoff);
  EXPECT_GT(order, 0.8);
  EXPECT_LT(order, 2.5);
  EXPECT_NEAR(extrapolated, kirchhoff, 0.02 * kirchhoff);
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

// Issue 8: the modal solve did not check that f is finite (a NaN load gave a NaN field).
TEST(ModalBasis, ModalSolveRefusesANonFiniteLoad) {
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.2, 0.1}, 4, 1, 1);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  ModalOptions options;
  options.mode_count = 4;
  const ModalBasis basis = ModalBasis::compute(body, fixed(*mesh, "xmin"), options);
  Eigen::VectorXd f = Eigen::VectorXd::Ones(basis.modes().rows());
  f[7] = NAN;
  for (ModalPrecision p : {ModalPrecision::Double, ModalPrecision::Single}) {
    try {
      basis.static_displacement(f, p);
      FAIL();
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("component y of node 3"), std::string::npos) << e.what();
    }
  }
}

// Records progress and cancels the job at the first report from inside the Lanczos iteration.
class CancelOnLanczosProgress final : public ProgressSink {
public:
  explicit CancelOnLanczosProgress(CancelToken& token) : m_token(token) {}
  void report(std::string_view, double fraction) override {
    std::lock_guard<std::mutex> lock(m_mutex);
    fractions.push_back(fraction);
    if (fraction > 0.1 && fraction < 0.95 && !m_token.cancelled()) {
      cancelled_at = std::chrono::steady_clock::now();
      m_token.cancel();
    }
  }
  std::vector<double> fractions;
  std::chrono::steady_clock::time_point cancelled_at;

private:
  CancelToken& m_token;
  std::mutex m_mutex;
};

// Issue 8: the eigensolve reported 0 and 1 only and checked the token before and after Spectra's
// compute(), so `modes --count 5000` ran for minutes silently and could not be stopped. Now each
// operator application checks the token: progress arrives from inside Lanczos (fractions strictly
// between the start and the end), and Cancelled follows the cancel within one triangular solve
// (≈ 1 ms here; 100 ms leaves room for a loaded CI machine and sanitizers).
TEST(ModalBasis, LanczosReportsProgressAndHonoursCancel) {
  auto mesh = test::box_mesh({-0.5, -0.5, 0}, {1.0, 1.0, 0.05}, 24, 24, 2);  // 6912 tets
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  ModalOptions options;
  options.mode_count = 300;  // a solve of several seconds; the test stops it after ≈ 0.2 s
  CancelToken token;
  CancelOnLanczosProgress sink(token);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(ModalBasis::compute(body, fixed(*mesh, "zmin"), options, &sink, &token), Cancelled);
  const auto end = std::chrono::steady_clock::now();
  ASSERT_TRUE(token.cancelled()) << "no progress report from inside the Lanczos iteration";
  EXPECT_LT(std::chrono::duration<double>(end - sink.cancelled_at).count(), 0.1);
  EXPECT_LT(std::chrono::duration<double>(end - start).count(), 2.0);
  for (std::size_t i = 1; i < sink.fractions.size(); ++i) EXPECT_GE(sink.fractions[i], sink.fractions[i - 1]);
}

// Issue 8: absurd requests started and ran out of memory or time. The estimate (Φ twice, the
// Krylov basis and its restart copy, the dense ncv² matrices, the factor) is checked before any factorisation.
TEST(ModalBasis, RequestsBeyondTheMemoryLimitAreRefusedUpFront) {
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.2, 0.1}, 10, 2, 2);  // 297 dofs, 252 free
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  ModalOptions options;
  options.mode_count = 100;
  options.memory_limit_bytes = 1'000'000;
  const std::vector<int> supports = fixed(*mesh, "xmin");
  // Basis 244 (100 + 160 capped at 252 − one block of 8): 8·(2·252·100 + 3·252·244 + 3·244²)
  // + 48·nnz(K_ff) ≈ 3.3 MB plus the factor.
  try {
    ModalBasis::compute(body, supports, options);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("modal analysis of 100 modes"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1 MB"), std::string::npos) << e.what();
  }
  options.memory_limit_bytes = 10'000'000;
  EXPECT_NO_THROW(ModalBasis::compute(body, supports, options));
  // The 21.5K-tet tile (16677 dofs, nnz(K) 607905) with 5000 modes: Φ alone is 1.3 GB, the
  // Krylov basis with its restart copy another 4 GB and the ncv² Rayleigh–Ritz matrices 2.4 GB.
  EXPECT_GT(modal_memory_estimate(16677, 5000, 10001, 607905), 5e9);
}

// Issue 8: an unwritable cache directory silently disabled the cache; the caller now hears it,
// once per call, and gets a valid basis anyway. (A file where the directory should be: refused
// even for root, unlike permissions.)
TEST(ModalBasis, AnUnwritableCacheIsReported) {
  const auto dir = test::fresh_temp_dir("modal-cache-unwritable");
  write_file_atomically(dir / "file", "not a directory");
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.2, 0.1}, 4, 1, 1);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  ModalOptions options;
  options.mode_count = 4;
  std::string warning = "stale";
  bool loaded = true;
  const ModalBasis basis =
      cached_modal_basis(body, fixed(*mesh, "xmin"), options, dir / "file" / "cache", &loaded, nullptr, nullptr, &warning);
  EXPECT_FALSE(loaded);
  EXPECT_EQ(basis.mode_count(), 4);
  EXPECT_NE(warning.find("modal basis not cached"), std::string::npos) << warning;
  EXPECT_NE(warning.find((dir / "file" / "cache").string()), std::string::npos) << warning;
  cached_modal_basis(body, fixed(*mesh, "xmin"), options, dir / "cache", &loaded, nullptr, nullptr, &warning);
  EXPECT_EQ(warning, "");
}

// Issue 8: a cache file with altered but finite values was used silently (max |u| 11× off). The
// file ends in a checksum of its contents now.
TEST(ModalBasis, AnAlteredCacheFileIsRefusedAndRecomputed) {
  const auto dir = test::fresh_temp_dir("modal-cache-altered");
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.2, 0.1}, 6, 1, 1);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  ModalOptions options;
  options.mode_count = 4;
  const auto supports = fixed(*mesh, "xmin");
  const ModalBasis original = cached_modal_basis(body, supports, options, dir);
  const Hash128 key = ModalBasis::cache_key(*body, supports, options);
  const auto file = dir / ("modes-" + key.hex() + ".bin");
  std::string bytes = read_file(file);
  // Scale the first eigenvalue (just after the 8-byte magic, 6 header words and the key) by 11.
  double lambda;
  const std::size_t at = 8 + 6 * 8 + 16;
  std::memcpy(&lambda, bytes.data() + at, 8);
  ASSERT_EQ(lambda, original.eigenvalues()[0]);
  lambda *= 11.0;
  std::memcpy(bytes.data() + at, &lambda, 8);
  write_file_atomically(file, bytes);
  try {
    ModalBasis::load(file, key);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("checksum"), std::string::npos) << e.what();
  }
  bool loaded = true;
  const ModalBasis again = cached_modal_basis(body, supports, options, dir, &loaded);
  EXPECT_FALSE(loaded);
  EXPECT_TRUE(again.eigenvalues() == original.eigenvalues());
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

// The single-vector shift-invert Lanczos the block solver replaced (issue 9), as the independent
// reference: Spectra over one-at-a-time CHOLMOD solves, on the M-orthogonal complement of the
// rigid motions R for a free body.
struct SpectraReference {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;  // restricted to the free dofs
};
SpectraReference spectra_reference(const ElasticBody& body, const std::vector<int>& fixed_dofs, int nev, double sigma) {
  const DofMap dofs(body.stiffness().rows(), fixed_dofs);
  const Eigen::SparseMatrix<double> k = dofs.restrict_matrix(body.stiffness());
  const Eigen::SparseMatrix<double> m = dofs.restrict_matrix(body.mass_matrix(MassKind::Lumped));
  const Eigen::MatrixXd rigid = fixed_dofs.empty() ? mass_orthonormal_rigid_modes(body, MassKind::Lumped) : Eigen::MatrixXd();
  const Eigen::MatrixXd mass_rigid = m * rigid;
  struct Op {
    using Scalar = double;
    const Eigen::SparseMatrix<double>* k;
    const Eigen::SparseMatrix<double>* m;
    const Eigen::MatrixXd* rigid;
    const Eigen::MatrixXd* mass_rigid;
    SparseCholesky factor;
    Eigen::Index rows() const { return k->rows(); }
    Eigen::Index cols() const { return k->cols(); }
    void set_shift(double s) { factor.factorize(Eigen::SparseMatrix<double>(*k - s * *m)); }
    void perform_op(const double* x, double* y) const {
      Eigen::Map<Eigen::VectorXd> out(y, rows());
      out = factor.solve(Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(x, rows())));
      if (rigid->cols() > 0) out -= *rigid * (mass_rigid->transpose() * out);
    }
  } op{&k, &m, &rigid, &mass_rigid, {}};
  struct Mass {
    using Scalar [[maybe_unused]] = double;  // Spectra's operator concept reads it
    const Eigen::SparseMatrix<double>* m;
    Eigen::Index rows() const { return m->rows(); }
    Eigen::Index cols() const { return m->cols(); }
    void perform_op(const double* x, double* y) const {
      Eigen::Map<Eigen::VectorXd>(y, rows()) = *m * Eigen::Map<const Eigen::VectorXd>(x, rows());
    }
  } mass{&m};
  Spectra::SymGEigsShiftSolver<Op, Mass, Spectra::GEigsMode::ShiftInvert> solver(op, mass, nev, 2 * nev + 1, sigma);
  Eigen::VectorXd start = Eigen::VectorXd::Ones(k.rows());
  for (Eigen::Index i = 0; i < start.size(); ++i) start[i] += std::sin(0.37 * static_cast<double>(i));
  if (rigid.cols() > 0) start -= rigid * (mass_rigid.transpose() * start);
  solver.init(start.data());
  solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-12, Spectra::SortRule::SmallestAlge);
  EXPECT_EQ(solver.info(), Spectra::CompInfo::Successful);
  return {solver.eigenvalues(), solver.eigenvectors()};
}

// Issue 9: the block Krylov–Schur solver must find what Spectra's Lanczos found, supported and
// free. Eigenvalues: both runs' Ritz values have relative residuals ≤ 1e-10 (block) and 1e-12
// (reference) on the shift-inverted operator, and a Ritz value's error is of the order of the
// squared residual over the gap, so 1e-9 relative is round-off of the factorisation with room.
// Vectors: their angle to the true eigenspace is ≲ residual/gap; modes closer than 1e-4
// relative form a cluster (the plate is square: many pairs are degenerate) and are compared
// as subspaces: Σ_{j ∈ cluster(i)} (φᵢᵀ M ψⱼ)² ≥ 1 − 1e-6, with the reference computed for two
// modes more so that no cluster of the first m is cut.
TEST(ModalBasis, BlockEigensolverAgreesWithSpectraLanczos) {
  auto mesh = test::box_mesh({-0.5, -0.5, 0}, {1.0, 1.0, 0.05}, 16, 16, 2);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  // 40 modes solve in blocks of 8; 20 on this small mesh in blocks of 4.
  for (const auto& [free, modes] : {std::pair{false, 40}, std::pair{true, 40}, std::pair{false, 20}, std::pair{true, 20}}) {
    SCOPED_TRACE(std::string(free ? "free" : "supported") + ", " + std::to_string(modes) + " modes");
    const std::vector<int> supports = free ? std::vector<int>{} : fixed(*mesh, "zmin");
    ModalOptions options;
    options.mode_count = modes;
    const ModalBasis basis = ModalBasis::compute(body, supports, options);
    const double sigma = free ? -0.01 * basis.eigenvalues()[0] : 0.0;
    const SpectraReference reference = spectra_reference(*body, supports, modes + 2, sigma);
    const DofMap dofs(body->stiffness().rows(), supports);
    const Eigen::SparseMatrix<double> m = dofs.restrict_matrix(body->mass_matrix(MassKind::Lumped));
    Eigen::MatrixXd phi(reference.vectors.rows(), modes);
    for (Eigen::Index j = 0; j < modes; ++j) phi.col(j) = dofs.restrict_vector(basis.modes().col(j));
    const Eigen::MatrixXd overlap = phi.transpose() * (m * reference.vectors);
    for (Eigen::Index i = 0; i < modes; ++i) {
      EXPECT_NEAR(basis.eigenvalues()[i], reference.values[i], 1e-9 * reference.values[i]) << "mode " << i;
      double captured = 0.0;
      for (Eigen::Index j = 0; j < modes + 2; ++j) {
        if (std::abs(reference.values[j] - reference.values[i]) <= 1e-4 * reference.values[i]) captured += overlap(i, j) * overlap(i, j);
      }
      EXPECT_GT(captured, 1.0 - 1e-6) << "mode " << i;
    }
    // Free body: every flexible mode is M-orthogonal to the rigid motions (deflation), to
    // round-off of the projection (1e-12 relative to the unit M-norm, with room).
    if (free) {
      EXPECT_LT((basis.rigid_modes().transpose() * (body->mass_matrix(MassKind::Lumped) * basis.modes())).cwiseAbs().maxCoeff(),
                1e-10);
    }
    expect_valid_eigenpairs(*body, basis, supports);
  }
}

// Issue 9: seeded start block, fixed block size and a sequential algorithm: bit-identical
// results on every run.
TEST(ModalBasis, BlockEigensolverIsDeterministic) {
  auto mesh = test::box_mesh({0, 0, 0}, {1.0, 0.2, 0.1}, 20, 4, 2);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  ModalOptions options;
  options.mode_count = 20;
  const ModalBasis a = ModalBasis::compute(body, fixed(*mesh, "xmin"), options);
  const ModalBasis b = ModalBasis::compute(body, fixed(*mesh, "xmin"), options);
  EXPECT_TRUE(a.eigenvalues() == b.eigenvalues());
  EXPECT_TRUE(a.modes() == b.modes());
}

}  // namespace
}  // namespace fissure
