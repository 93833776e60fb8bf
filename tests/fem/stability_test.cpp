// Numerical stability sweep (issue 3): extreme materials and scales, and a near-flat sliver.
// Every case must give finite results with a residual ≤ 1e-8, or a clear refusal.

#include "fissure/base/error.hpp"
#include "fissure/fem/load.hpp"
#include "fissure/fem/static_solver.hpp"
#include "fissure/fem/stress.hpp"

#include "fem_test_meshes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace fissure {
namespace {

struct Outcome {
  bool solved = false;
  bool refused = false;
  double residual = 0.0;
  std::string message;
};

Outcome run(std::shared_ptr<const TetMesh> mesh, const ElasticMaterial& m,
            const std::vector<SupportSpec>& supports, const LoadSpec& load) {
  Outcome out;
  try {
    auto body = std::make_shared<const ElasticBody>(mesh, m);
    const StaticSolver solver(body, resolve_supports(*mesh, supports));
    const StaticSolution sol = solver.solve(assemble_load(*mesh, load));
    StressField s;
    Eigen::VectorXd smax;
    compute_stress_and_max_principal(*mesh, body->gradients(), m, sol.displacement, s, smax);
    EXPECT_TRUE(sol.displacement.allFinite());
    EXPECT_TRUE(s.allFinite());
    EXPECT_TRUE(smax.allFinite());
    out.solved = true;
    out.residual = sol.relative_residual;
  } catch (const Error& e) {
    out.refused = true;
    out.message = e.what();
  }
  return out;
}

TEST(Stability, MaterialAndScaleSweep) {
  int solved = 0;
  for (double e : {1e3, 1e6, 3e10, 1e12}) {
    for (double nu : {0.0, 0.25, 0.45, 0.49}) {
      for (double scale : {1e-3, 1.0, 1e3}) {
        auto mesh = test::box_mesh({0, 0, 0}, Eigen::Vector3d(1.0, 0.2, 0.1) * scale, 10, 2, 2);
        LoadSpec load = parse_load("xmax=0,0,-1");
        load.force *= e * scale * scale * 1e-6;  // a strain of ~1e-6 whatever E and size
        const Outcome o = run(mesh, ElasticMaterial{e, nu, 2400}, {parse_support("xmin")}, load);
        ASSERT_TRUE(o.solved || o.refused);
        if (o.solved) {
          ++solved;
          EXPECT_LE(o.residual, 1e-8) << "E " << e << " nu " << nu << " scale " << scale;
        } else {
          EXPECT_FALSE(o.message.empty());
          std::printf("refused: E %g nu %g scale %g: %s\n", e, nu, scale, o.message.c_str());
        }
      }
    }
  }
  // Double precision is scale-invariant (fem-pitfalls.md §2.6): none of these should need refusing.
  EXPECT_EQ(solved, 48);
}

// A near-flat sliver (the 4 corners of a square, one lifted by ε) glued between two caps. With
// ε = 1e-6 its min dihedral is ~1e-4°; cond(K) grows like 1/ε but stays solvable in double.
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
    // apex; (0,1,3) and (1,2,3) are its bottom. (The caps were once on the wrong faces, stacked
    // on the sliver: TetMesh now refuses that.)
    Eigen::MatrixX4i tets(5, 4);
    tets << 0, 1, 2, 3, 0, 1, 3, 5, 1, 2, 3, 5, 0, 1, 2, 4, 0, 2, 3, 4;
    for (int t = 0; t < 5; ++t) {
      const Eigen::Vector3d a = nodes.row(tets(t, 0)), b = nodes.row(tets(t, 1)), c = nodes.row(tets(t, 2)),
                            d = nodes.row(tets(t, 3));
      if ((b - a).dot((c - a).cross(d - a)) < 0) std::swap(tets(t, 2), tets(t, 3));
    }
    std::shared_ptr<const TetMesh> mesh;
    try {
      mesh = std::make_shared<const TetMesh>(nodes, tets, "sliver");
    } catch (const InvalidInput& e) {
      FAIL() << "eps " << eps << ": " << e.what();
    }
    EXPECT_LT(mesh->quality().min_dihedral_deg, eps < 1e-3 ? 0.1 : 10.0);
    const Outcome o = run(mesh, test::concrete(), {parse_support("ball:0.5,0.5,-1,0.01"), parse_support("ball:0,0,0,0.01@z"),
                                                   parse_support("ball:1,0,0,0.01@yz")},
                          parse_load("box:-1,2,-1,2,-0.5,2=0,0,-100"));
    ASSERT_TRUE(o.solved || o.refused);
    if (o.solved) {
      EXPECT_LE(o.residual, 1e-8) << "eps " << eps;
    } else {
      std::printf("sliver eps %g refused: %s\n", eps, o.message.c_str());
    }
  }
}

}  // namespace
}  // namespace fissure
