#include "fissure/base/error.hpp"
#include "fissure/fem/assembly.hpp"
#include "fissure/fem/elastic_body.hpp"
#include "fissure/fem/rigid_modes.hpp"

#include "fem_test_meshes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstring>

namespace fissure {
namespace {

// Reference element stiffness from the textbook form K_e = V Bᵀ D B, with B the 6×12
// strain-displacement matrix (engineering shear): an independent path to the same numbers.
Eigen::Matrix<double, 12, 12> reference_element_stiffness(const TetMesh& mesh, int t, const ElasticMaterial& m) {
  Eigen::Matrix3d j;
  const Eigen::Vector3d x0 = mesh.nodes().row(mesh.tets()(t, 0));
  for (int a = 1; a < 4; ++a) j.col(a - 1) = mesh.nodes().row(mesh.tets()(t, a)).transpose() - x0;
  const Eigen::Matrix3d inv = j.inverse();
  Eigen::Matrix<double, 3, 4> g;
  g.rightCols<3>() = inv.transpose();
  g.col(0) = -g.rightCols<3>().rowwise().sum();
  Eigen::Matrix<double, 6, 12> b = Eigen::Matrix<double, 6, 12>::Zero();
  for (int a = 0; a < 4; ++a) {
    const double gx = g(0, a), gy = g(1, a), gz = g(2, a);
    b(0, 3 * a) = gx;
    b(1, 3 * a + 1) = gy;
    b(2, 3 * a + 2) = gz;
    b(3, 3 * a + 1) = gz;
    b(3, 3 * a + 2) = gy;
    b(4, 3 * a) = gz;
    b(4, 3 * a + 2) = gx;
    b(5, 3 * a) = gy;
    b(5, 3 * a + 1) = gx;
  }
  return mesh.volumes()[t] * b.transpose() * m.elasticity_matrix() * b;
}

TEST(Assembly, UnitTetMatchesTextbookBtDB) {
  Eigen::MatrixX3d nodes(4, 3);
  nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::MatrixX4i tets(1, 4);
  tets << 0, 1, 2, 3;
  auto mesh = std::make_shared<const TetMesh>(nodes, tets);
  const ElasticMaterial m{1.0e3, 0.3, 1.0};
  const ElasticBody body(mesh, m);
  const Eigen::MatrixXd k = Eigen::MatrixXd(body.stiffness());
  const Eigen::Matrix<double, 12, 12> ref = reference_element_stiffness(*mesh, 0, m);
  // Both are exact integrals of the same polynomial; they differ only by summation order,
  // i.e. a few ulps of the largest entry.
  EXPECT_LT((k - ref).cwiseAbs().maxCoeff(), 1e-13 * ref.cwiseAbs().maxCoeff());
  EXPECT_DOUBLE_EQ(mesh->volumes()[0], 1.0 / 6.0);
}

TEST(Assembly, StiffnessIsSymmetricWithRigidNullSpace) {
  auto mesh = test::perturbed_box(3, 0.2, 11);
  const ElasticBody body(mesh, test::concrete());
  const SparseMatrixD& k = body.stiffness();
  const double scale = Eigen::MatrixXd(k).cwiseAbs().maxCoeff();
  // Symmetry: each element block is symmetric in exact arithmetic; the computed K_ab and K_ba
  // use the same products in a different order, so the mismatch is round-off.
  const SparseMatrixD asym = k - SparseMatrixD(k.transpose());
  double worst = 0.0;
  for (int c = 0; c < asym.outerSize(); ++c)
    for (SparseMatrixD::InnerIterator it(asym, c); it; ++it) worst = std::max(worst, std::abs(it.value()));
  EXPECT_LT(worst, 1e-14 * scale);
  // K r = 0 for the 6 rigid motions (relative to ‖K‖·‖r‖, round-off of row sums).
  const Eigen::MatrixXd r = rigid_body_modes(*mesh, 0);
  const Eigen::MatrixXd kr = k * r;
  EXPECT_LT(kr.cwiseAbs().maxCoeff(), 1e-12 * scale * r.cwiseAbs().maxCoeff());
  // Row sums vanish (translations).
  const Eigen::VectorXd ones_x = r.col(0);
  EXPECT_LT((k * ones_x).cwiseAbs().maxCoeff(), 1e-12 * scale);
}

TEST(Assembly, EveryElementMatchesTheReference) {
  auto mesh = test::perturbed_box(2, 0.2, 3);
  const ElasticMaterial m = test::concrete();
  const ElasticBody body(mesh, m);
  Eigen::MatrixXd reference = Eigen::MatrixXd::Zero(body.stiffness().rows(), body.stiffness().cols());
  for (int t = 0; t < mesh->tet_count(); ++t) {
    const auto ke = reference_element_stiffness(*mesh, t, m);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        reference.block<3, 3>(3 * mesh->tets()(t, a), 3 * mesh->tets()(t, b)) += ke.block<3, 3>(3 * a, 3 * b);
  }
  const Eigen::MatrixXd k(body.stiffness());
  EXPECT_LT((k - reference).cwiseAbs().maxCoeff(), 1e-13 * reference.cwiseAbs().maxCoeff());
}

TEST(Assembly, MassesCarryTheTotalMass) {
  auto mesh = test::perturbed_box(3, 0.15, 5);
  const double rho = 2400.0;
  const ElasticBody body(mesh, ElasticMaterial{3e10, 0.2, rho});
  const double total = rho * mesh->total_volume();
  const Eigen::VectorXd ex = rigid_body_modes(*mesh, 0).col(0);
  // Translation along x: uᵀMu is the total mass for both lumped and consistent M, to round-off.
  EXPECT_NEAR(ex.dot(body.mass_times(MassKind::Lumped, ex)), total, 1e-12 * total);
  EXPECT_NEAR(ex.dot(body.mass_times(MassKind::Consistent, ex)), total, 1e-12 * total);
  EXPECT_TRUE((body.lumped_mass().array() > 0.0).all());
  // Consistent M is symmetric positive definite: its smallest eigenvalue is positive.
  const Eigen::MatrixXd mc(body.mass_matrix(MassKind::Consistent));
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(mc).eigenvalues().minCoeff(), 0.0);
}

TEST(Assembly, ThreadCountDoesNotChangeTheBits) {
  auto mesh = test::perturbed_box(6, 0.2, 9);
  const ElasticBody one(mesh, test::concrete(), 1);
  const ElasticBody two(mesh, test::concrete(), 2);
  ASSERT_EQ(one.stiffness().nonZeros(), two.stiffness().nonZeros());
  EXPECT_EQ(std::memcmp(one.stiffness().valuePtr(), two.stiffness().valuePtr(),
                        sizeof(double) * static_cast<std::size_t>(one.stiffness().nonZeros())),
            0);
}

// The assembly before issue 9, kept as the reference: every tet's 144 doubles computed first,
// then scattered in tet order. The batched assembly must give K's values byte for byte.
SparseMatrixD reference_stiffness(const TetMesh& mesh, const TetGradients& gradients, const ElasticMaterial& material,
                                  const StiffnessPattern& pattern) {
  const int n_tets = mesh.tet_count();
  const double lambda = material.lame_lambda();
  const double mu = material.shear_modulus();
  std::vector<double> blocks(static_cast<std::size_t>(n_tets) * 144);
  for (int t = 0; t < n_tets; ++t) {
    Eigen::Vector3d g[4];
    for (int a = 0; a < 4; ++a) g[a] = gradients.gradient(t, a);
    const double v = gradients.volumes[t];
    double* out = blocks.data() + static_cast<std::size_t>(t) * 144;
    for (int b = 0; b < 4; ++b) {
      for (int a = 0; a < 4; ++a) {
        const double dot = mu * g[a].dot(g[b]);
        double* blk = out + 9 * (4 * b + a);
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i)
            blk[3 * j + i] = v * (lambda * g[a][i] * g[b][j] + mu * g[b][i] * g[a][j] + (i == j ? dot : 0.0));
      }
    }
  }
  SparseMatrixD k = pattern.empty_matrix();
  double* values = k.valuePtr();
  for (int t = 0; t < n_tets; ++t) {
    const double* blk = blocks.data() + static_cast<std::size_t>(t) * 144;
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a, blk += 9)
        for (int j = 0; j < 3; ++j) {
          double* col = values + pattern.block_slot(t, a, b, j);
          col[0] += blk[3 * j];
          col[1] += blk[3 * j + 1];
          col[2] += blk[3 * j + 2];
        }
  }
  return k;
}

TEST(Assembly, BatchedAssemblyGivesTheBytesOfTheWholeBufferAssembly) {
  // 10,368 tets: ten full batches of 1,024 and a partial one.
  auto mesh = test::perturbed_box(12, 0.2, 11);
  const TetGradients gradients = compute_tet_gradients(*mesh);
  const StiffnessPattern pattern(*mesh);
  const SparseMatrixD expected = reference_stiffness(*mesh, gradients, test::concrete(), pattern);
  for (int threads : {1, 2}) {
    const SparseMatrixD k = assemble_stiffness(*mesh, gradients, test::concrete(), pattern, threads);
    ASSERT_EQ(k.nonZeros(), expected.nonZeros());
    EXPECT_EQ(std::memcmp(k.valuePtr(), expected.valuePtr(), sizeof(double) * static_cast<std::size_t>(k.nonZeros())), 0)
        << threads << " threads";
  }
}

TEST(ElasticMaterial, ValidationNamesTheParameter) {
  auto message = [](ElasticMaterial m) {
    try {
      m.validate();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(test::concrete()), "");
  EXPECT_NE(message(ElasticMaterial{3e10, 0.62, 2400}).find("poisson_ratio 0.62 is outside [0, 0.5)"),
            std::string::npos);
  EXPECT_NE(message(ElasticMaterial{3e10, 0.5, 2400}).find("poisson_ratio 0.5"), std::string::npos);
  EXPECT_NE(message(ElasticMaterial{0.0, 0.2, 2400}).find("youngs_modulus 0 is outside (0, inf] Pa"),
            std::string::npos);
  EXPECT_NE(message(ElasticMaterial{-1.0, 0.2, 2400}).find("youngs_modulus -1"), std::string::npos);
  EXPECT_NE(message(ElasticMaterial{3e10, 0.2, std::nan("")}).find("density nan is not a finite number"), std::string::npos);
  // Issue 8: inf used to read "youngs_modulus inf is outside (0, inf] Pa", which is self-contradictory.
  const ParameterInfo& e_info = elastic_material_parameters()[0];
  EXPECT_EQ(parameter_problem(e_info, INFINITY, "--E"), "--E inf is not a finite number");
  EXPECT_EQ(parameter_problem(e_info, -INFINITY, "--E"), "--E -inf is not a finite number");
  EXPECT_EQ(parameter_problem(e_info, 1e-7, "--E"), "");
  EXPECT_EQ(parameter_problem(e_info, -1e-7, "--E"), "--E -1e-07 is outside (0, inf] Pa");  // significant digits
  EXPECT_THROW(ElasticBody(test::box_mesh({0, 0, 0}, {1, 1, 1}, 1, 1, 1), ElasticMaterial{3e10, 0.5, 1}),
               InvalidInput);
}

}  // namespace
}  // namespace fissure
