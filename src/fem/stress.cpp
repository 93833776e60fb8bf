#include "fissure/fem/stress.hpp"

#include "fissure/base/error.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace fissure {
namespace {

void check_displacements(const TetMesh& mesh, const Eigen::VectorXd& u) {
  if (u.size() != 3 * static_cast<Eigen::Index>(mesh.node_count())) {
    throw InvalidInput("stress: displacement vector has " + std::to_string(u.size()) +
                       " entries, the mesh needs " + std::to_string(3 * mesh.node_count()));
  }
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    if (!std::isfinite(u[i])) {
      throw InvalidInput("stress: displacement of node " + std::to_string(i / 3) + " is not finite");
    }
  }
}

// arccos on [−1, 1], Abramowitz & Stegun 4.4.46 (|error| ≤ 2e-8 rad), branch-free so loops
// vectorise: acos(x) = √(1−|x|)·P(|x|) for x ≥ 0, π − that for x < 0.
inline double acos_polynomial(double x) {
  const double ax = x < 0.0 ? -x : x;
  const double p =
      1.5707963050 +
      ax * (-0.2145988016 +
            ax * (0.0889789874 +
                  ax * (-0.0501743046 +
                        ax * (0.0308918810 + ax * (-0.0170881256 + ax * (0.0066700901 + ax * -0.0012624911))))));
  const double r = std::sqrt(1.0 - ax) * p;
  return x < 0.0 ? std::numbers::pi - r : r;
}

// cos on [0, π/3]: Taylor series to x¹⁶; the first omitted term is < 4e-16.
inline double cos_small(double x) {
  const double x2 = x * x;
  double s = 1.0 / 20922789888000.0;          // 1/16!
  s = s * x2 - 1.0 / 87178291200.0;           // 1/14!
  s = s * x2 + 1.0 / 479001600.0;             // 1/12!
  s = s * x2 - 1.0 / 3628800.0;               // 1/10!
  s = s * x2 + 1.0 / 40320.0;                 // 1/8!
  s = s * x2 - 1.0 / 720.0;                   // 1/6!
  s = s * x2 + 1.0 / 24.0;                    // 1/4!
  s = s * x2 - 1.0 / 2.0;                     // 1/2!
  return s * x2 + 1.0;
}

// λ_max of the symmetric tensor (a, b, c, d=yz, e=xz, f=xy). Trigonometric solution: with
// q = tr/3, p = √(‖A − qI‖²_F / 6) and B = (A − qI)/p, the eigenvalues of B solve β³ − 3β = det B,
// the largest being 2cos(acos(det B / 2)/3). The polynomial arccos is refined by two Newton steps
// on that cubic (quadratic convergence from 1e-8 to round-off away from a double root, where the
// arccos error itself vanishes).
inline double max_principal(double a, double b, double c, double d, double e, double f) {
  // Written with selects only (no branches, no guarded divisions) so GCC vectorises the loop
  // that inlines it.
  const double q = (a + b + c) * (1.0 / 3.0);
  const double a1 = a - q, b1 = b - q, c1 = c - q;
  const double off = d * d + e * e + f * f;
  const double p2 = (a1 * a1 + b1 * b1 + c1 * c1 + 2.0 * off) * (1.0 / 6.0);
  const double p = std::sqrt(p2);
  const double det = a1 * (b1 * c1 - d * d) - f * (f * c1 - d * e) + e * (f * d - b1 * e);
  const bool isotropic = !(p > 0.0);
  const double safe_p = isotropic ? 1.0 : p;
  double r = det / (2.0 * safe_p * safe_p * safe_p);
  r = r < -1.0 ? -1.0 : (r > 1.0 ? 1.0 : r);
  double t = 2.0 * cos_small(acos_polynomial(r) * (1.0 / 3.0));
  // Two Newton steps on t³ − 3t − 2r = 0; skipped where the derivative vanishes (double root).
  const double g1 = t * t * t - 3.0 * t - 2.0 * r;
  const double dg1 = 3.0 * t * t - 3.0;
  const double step1 = g1 / (dg1 > 1e-6 ? dg1 : 1.0);
  t -= dg1 > 1e-6 ? step1 : 0.0;
  const double g2 = t * t * t - 3.0 * t - 2.0 * r;
  const double dg2 = 3.0 * t * t - 3.0;
  const double step2 = g2 / (dg2 > 1e-6 ? dg2 : 1.0);
  t -= dg2 > 1e-6 ? step2 : 0.0;
  return isotropic ? q : q + p * t;
}

}  // namespace

Eigen::Matrix3d voigt_to_tensor(const Eigen::Matrix<double, 6, 1>& v) {
  Eigen::Matrix3d s;
  s << v[0], v[5], v[4], v[5], v[1], v[3], v[4], v[3], v[2];
  return s;
}

Eigen::Matrix<double, 6, 1> tensor_to_voigt(const Eigen::Matrix3d& s) {
  Eigen::Matrix<double, 6, 1> v;
  v << s(0, 0), s(1, 1), s(2, 2), s(1, 2), s(0, 2), s(0, 1);
  return v;
}

PrincipalStresses principal_stresses(const Eigen::Matrix<double, 6, 1>& voigt) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(voigt_to_tensor(voigt));
  PrincipalStresses out;
  // Eigen sorts ascending; reverse to descending.
  for (int k = 0; k < 3; ++k) {
    out.values[k] = solver.eigenvalues()[2 - k];
    out.directions.col(k) = solver.eigenvectors().col(2 - k);
  }
  return out;
}

double max_principal_stress(const Eigen::Matrix<double, 6, 1>& v) {
  return max_principal(v[0], v[1], v[2], v[3], v[4], v[5]);
}

StressField compute_stress(const TetMesh& mesh, const TetGradients& gradients,
                           const ElasticMaterial& material, const Eigen::VectorXd& u) {
  StressField stress;
  Eigen::VectorXd unused;
  compute_stress_and_max_principal(mesh, gradients, material, u, stress, unused);
  return stress;
}

void compute_stress_and_max_principal(const TetMesh& mesh, const TetGradients& gradients,
                                      const ElasticMaterial& material, const Eigen::VectorXd& u,
                                      StressField& stress, Eigen::VectorXd& max_principal_out) {
  check_displacements(mesh, u);
  const int n = mesh.tet_count();
  stress.resize(n, 6);
  max_principal_out.resize(n);
  const double lambda = material.lame_lambda();
  const double mu = material.shear_modulus();
  const int* tet = mesh.tets().data();  // column-major: node k of tet t at tet[k·n + t]
  const double* g = gradients.g.data();  // column k of tet t at g[k·n + t]
  const double* ud = u.data();
  double* s = stress.data();
  double* smax = max_principal_out.data();

  // Structure-of-arrays loop: unit-stride reads of gradients and writes of the six stress
  // components; the only gathers are the 12 displacement values.
#pragma GCC ivdep
  for (int t = 0; t < n; ++t) {
    const int n0 = tet[t], n1 = tet[n + t], n2 = tet[2 * n + t], n3 = tet[3 * n + t];
    const double u0x = ud[3 * n0], u0y = ud[3 * n0 + 1], u0z = ud[3 * n0 + 2];
    // Relative displacements of nodes 1–3 (node 0's gradient is minus the sum of the others).
    const double d1x = ud[3 * n1] - u0x, d1y = ud[3 * n1 + 1] - u0y, d1z = ud[3 * n1 + 2] - u0z;
    const double d2x = ud[3 * n2] - u0x, d2y = ud[3 * n2 + 1] - u0y, d2z = ud[3 * n2 + 2] - u0z;
    const double d3x = ud[3 * n3] - u0x, d3y = ud[3 * n3 + 1] - u0y, d3z = ud[3 * n3 + 2] - u0z;
    const double g1x = g[t], g1y = g[n + t], g1z = g[2 * n + t];
    const double g2x = g[3 * n + t], g2y = g[4 * n + t], g2z = g[5 * n + t];
    const double g3x = g[6 * n + t], g3y = g[7 * n + t], g3z = g[8 * n + t];
    // Displacement gradient H_ij = ∂u_i/∂x_j.
    const double hxx = d1x * g1x + d2x * g2x + d3x * g3x;
    const double hxy = d1x * g1y + d2x * g2y + d3x * g3y;
    const double hxz = d1x * g1z + d2x * g2z + d3x * g3z;
    const double hyx = d1y * g1x + d2y * g2x + d3y * g3x;
    const double hyy = d1y * g1y + d2y * g2y + d3y * g3y;
    const double hyz = d1y * g1z + d2y * g2z + d3y * g3z;
    const double hzx = d1z * g1x + d2z * g2x + d3z * g3x;
    const double hzy = d1z * g1y + d2z * g2y + d3z * g3y;
    const double hzz = d1z * g1z + d2z * g2z + d3z * g3z;
    const double volumetric = lambda * (hxx + hyy + hzz);
    const double sxx = volumetric + 2.0 * mu * hxx;
    const double syy = volumetric + 2.0 * mu * hyy;
    const double szz = volumetric + 2.0 * mu * hzz;
    const double syz = mu * (hyz + hzy);
    const double sxz = mu * (hxz + hzx);
    const double sxy = mu * (hxy + hyx);
    s[t] = sxx;
    s[n + t] = syy;
    s[2 * n + t] = szz;
    s[3 * n + t] = syz;
    s[4 * n + t] = sxz;
    s[5 * n + t] = sxy;
    smax[t] = max_principal(sxx, syy, szz, syz, sxz, sxy);
  }
}

}  // namespace fissure
