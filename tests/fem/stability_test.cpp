// Numerical stability sweep (issue 3): extreme materials and scales, and a near-flat sliver.
// Every case here is solvable in double precision and must be solved: a refusal fails the test.
// What is checked does not come from the solver: the residual is recomputed from K, and the
// answers are compared with analytic solutions or with the exact scaling laws of linear
// elasticity.

#include "fissure/base/error.hpp"
#include "fissure/fem/load.hpp"
#include "fissure/fem/static_solver.hpp"
#include "fissure/fem/stress.hpp"

#include "fem_test_meshes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace fissure {
namespace {

// ‖K_ff u_f − f_f‖ / ‖f_f‖ over the free dofs, from the body's K and the test's own products.
double independent_residual(const ElasticBody& body, const std::vector<int>& fixed, const Eigen::VectorXd& u,
                            const Eigen::VectorXd& f) {
  const DofMap dofs(body.stiffness().rows(), fixed);
  const Eigen::VectorXd r = dofs.restrict_vector(body.stiffness() * u - f);
  return r.norm() / dofs.restrict_vector(f).norm();
}

// Total force the supports exert, recomputed: Σ over fixed dofs of (K u − f).
Eigen::Vector3d independent_reaction(const ElasticBody& body, const std::vector<int>& fixed, const Eigen::VectorXd& u,
                                     const Eigen::VectorXd& f) {
  const Eigen::VectorXd r = body.stiffness() * u - f;
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (int d : fixed) total[d % 3] += r[d];
  return total;
}

// A bar L × 0.2L × 0.1L on rollers (x fixed at x = 0, y at y = 0, z at z = 0), pulled along x by
// F = E·A·1e-6: the exact solution u = (εx, −νεy, −νεz), ε = 1e-6, is linear, so linear tets
// must reproduce it to round-off at every E, ν and scale. A cantilever (transverse tip load) on
// the same mesh is the ill-conditioned case; it has no closed form on this coarse mesh, but
// scaling does: u(L·s, E, F·E·s²) = s·u(L, 1, F), so u/(s·1e-6) must agree across all E and s
// for each ν (to the round-off of cond(K) ≲ 1e7, hence 1e-8).
TEST(Stability, MaterialAndScaleSweep) {
  for (double nu : {0.0, 0.25, 0.45, 0.49}) {
    Eigen::VectorXd reference;
    for (double e : {1e3, 1e6, 3e10, 1e12}) {
      for (double scale : {1e-3, 1.0, 1e3}) {
        const std::string where = "E " + std::to_string(e) + " nu " + std::to_string(nu) + " scale " + std::to_string(scale);
        auto mesh = test::box_mesh({0, 0, 0}, Eigen::Vector3d(1.0, 0.2, 0.1) * scale, 10, 2, 2);
        auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{e, nu, 2400});
        const double strain = 1e-6, area = 0.02 * scale * scale;

        // Axial bar: exact.
        const std::vector<int> rollers =
            resolve_supports(*mesh, {parse_support("xmin@x"), parse_support("ymin@y"), parse_support("zmin@z")});
        LoadSpec pull = parse_load("xmax=1,0,0");
        pull.force *= e * area * strain;
        const Eigen::VectorXd f_bar = assemble_load(*mesh, pull);
        const StaticSolution bar = StaticSolver(body, rollers).solve(f_bar);
        EXPECT_LT(independent_residual(*body, rollers, bar.displacement, f_bar), 1e-10) << where;
        double worst = 0.0;
        for (int v = 0; v < mesh->node_count(); ++v) {
          const Eigen::Vector3d x = mesh->nodes().row(v);
          const Eigen::Vector3d exact(strain * x.x(), -nu * strain * x.y(), -nu * strain * x.z());
          worst = std::max(worst, (bar.displacement.segment<3>(3 * v) - exact).cwiseAbs().maxCoeff());
        }
        // Round-off of cond(K) ~1e4 on the elongation scale ε·L.
        EXPECT_LT(worst, 1e-10 * strain * scale) << where;
        const StressField s = compute_stress(*body, bar.displacement);
        EXPECT_LT((s.col(0).array() - e * strain).abs().maxCoeff(), 1e-8 * e * strain) << where;

        // Cantilever: independent residual, equilibrium, and the scaling law.
        const std::vector<int> clamp = resolve_supports(*mesh, {parse_support("xmin")});
        LoadSpec tip = parse_load("xmax=0,0,-1");
        tip.force *= e * scale * scale * 1e-6;  // a strain of ~1e-6 whatever E and size
        const Eigen::VectorXd f_tip = assemble_load(*mesh, tip);
        const StaticSolution cantilever = StaticSolver(body, clamp).solve(f_tip);
        EXPECT_LT(independent_residual(*body, clamp, cantilever.displacement, f_tip), 1e-10) << where;
        const Eigen::Vector3d reaction = independent_reaction(*body, clamp, cantilever.displacement, f_tip);
        EXPECT_LT((reaction + tip.force).norm(), 1e-9 * tip.force.norm()) << where;
        const Eigen::VectorXd normalised = cantilever.displacement / (scale * 1e-6);
        if (reference.size() == 0) {
          reference = normalised;
        } else {
          EXPECT_LT((normalised - reference).norm(), 1e-8 * reference.norm()) << where;
        }
        StressField stress;
        Eigen::VectorXd smax;
        compute_stress_and_max_principal(*body, cantilever.displacement, stress, smax);
        EXPECT_TRUE(smax.allFinite()) << where;
      }
    }
  }
}

// A near-flat sliver (the 4 corners of a square, one lifted by ε) glued between two caps. With
// ε = 1e-6 its min dihedral is ~1e-4°; cond(K) grows like 1/ε (~1e6·1e3 = 1e9 at ε = 1e-6), which
// double precision with refinement still solves: every case must be solved (it once passed when
// all were refused). Checked independently: the residual from K, the support reactions summing
// to minus the load (equilibrium of the whole body), and the loaded apex moving the way it is
// pushed.
TEST(Stability, NearFlatSliver) {
  for (double eps : {1e-2, 1e-4, 1e-6}) {
    Eigen::MatrixX3d nodes(6, 3);
    nodes << 0, 0, 0,  //
        1, 0, 0,       //
        1, 1, eps,     //
        0, 1, 0,       //
        0.5, 0.5, 1,   // top apex
        0.5, 0.5, -1;  // bottom apex
    // The sliver (0,1,2,3) and caps on its four faces, each on the outer side: node 2 is lifted,
    // so the faces through the diagonal 0–2, (0,1,2) and (0,2,3), are its top and take the top
    // apex; (0,1,3) and (1,2,3) are its bottom.
    Eigen::MatrixX4i tets(5, 4);
    tets << 0, 1, 2, 3, 0, 1, 3, 5, 1, 2, 3, 5, 0, 1, 2, 4, 0, 2, 3, 4;
    for (int t = 0; t < 5; ++t) {
      const Eigen::Vector3d a = nodes.row(tets(t, 0)), b = nodes.row(tets(t, 1)), c = nodes.row(tets(t, 2)),
                            d = nodes.row(tets(t, 3));
      if ((b - a).dot((c - a).cross(d - a)) < 0) std::swap(tets(t, 2), tets(t, 3));
    }
    auto mesh = std::make_shared<const TetMesh>(nodes, tets, "sliver");
    EXPECT_LT(mesh->quality().min_dihedral_deg, eps < 1e-3 ? 0.1 : 10.0);
    auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
    const std::vector<int> fixed =
        resolve_supports(*mesh, {parse_support("ball:0.5,0.5,-1,0.01"), parse_support("ball:0,0,0,0.01@z"),
                                 parse_support("ball:1,0,0,0.01@yz")});
    // Every upward-facing boundary face: the top cap's four sides.
    const LoadSpec load = parse_load("box:-1,2,-1,2,-0.5,2^0,0,1=0,0,-100");
    const Eigen::VectorXd f = assemble_load(*mesh, load);
    StaticSolution sol;
    ASSERT_NO_THROW(sol = StaticSolver(body, fixed).solve(f)) << "eps " << eps;
    // The solver's contract is a residual ≤ max_residual (1e-8) after refinement (ε = 1e-6 reaches
    // ≈ 7e-10, above the 1e-10 target but within it): checked from K here, and the solver's own
    // report must agree with it (same quantity, different summation: within a factor 1.5).
    const double residual = independent_residual(*body, fixed, sol.displacement, f);
    EXPECT_LT(residual, 1e-8) << "eps " << eps;
    EXPECT_LT(sol.relative_residual, 1.5 * residual + 1e-16) << "eps " << eps;
    EXPECT_GT(sol.relative_residual, residual / 1.5) << "eps " << eps;
    const Eigen::Vector3d reaction = independent_reaction(*body, fixed, sol.displacement, f);
    EXPECT_LT((reaction - Eigen::Vector3d(0, 0, 100)).norm(), 1e-8 * 100) << "eps " << eps;
    EXPECT_LT((sol.support_reaction - reaction).norm(), 1e-8 * 100) << "eps " << eps;
    const double apex_deflection = -sol.displacement[3 * 4 + 2];
    EXPECT_GT(apex_deflection, 0.0) << "eps " << eps;  // pushed down, it moves down
    const StressField s = compute_stress(*body, sol.displacement);
    EXPECT_TRUE(s.allFinite()) << "eps " << eps;
  }
}

}  // namespace
}  // namespace fissure
