#include "fissure/fem/stress.hpp"

#include "fissure/base/error.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <bit>
#include <cstdint>
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
  if (u.allFinite()) return;
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    if (!std::isfinite(u[i])) {
      throw InvalidInput("stress: displacement of " + mesh.node_label(static_cast<int>(i / 3)) + " is not finite");
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

// The unit eigenvector of the largest eigenvalue `lambda` of the symmetric tensor
// (a, b, c, d=yz, e=xz, f=xy), all already divided by the tensor's largest component. The rows of
// A − λI span the orthogonal complement of the eigenvector, so the cross product of two of them
// is parallel to it; of the three, the longest is the best conditioned (its length is
// |λ₂ − λ||λ₃ − λ| for the best pair). When even that is at round-off level relative to the rows
// (|cross| ≤ √ε·|row|², i.e. λ is within √ε of a second eigenvalue: rank(A − λI) ≤ 1), the
// cross product's direction is noise, while any vector orthogonal to the largest row lies in
// the eigenspace to within √ε: that is taken instead (crossover at √ε balances the two errors,
// ε/ρ and ρ, for a relative gap ρ). All selects, no branches, so the loop vectorises.
inline void max_direction(double a, double b, double c, double d, double e, double f, double lambda, double& vx,
                          double& vy, double& vz) {
  const double r0x = a - lambda, r0y = f, r0z = e;
  const double r1x = f, r1y = b - lambda, r1z = d;
  const double r2x = e, r2y = d, r2z = c - lambda;
  // Cross products of row pairs.
  const double c01x = r0y * r1z - r0z * r1y, c01y = r0z * r1x - r0x * r1z, c01z = r0x * r1y - r0y * r1x;
  const double c02x = r0y * r2z - r0z * r2y, c02y = r0z * r2x - r0x * r2z, c02z = r0x * r2y - r0y * r2x;
  const double c12x = r1y * r2z - r1z * r2y, c12y = r1z * r2x - r1x * r2z, c12z = r1x * r2y - r1y * r2x;
  const double n01 = c01x * c01x + c01y * c01y + c01z * c01z;
  const double n02 = c02x * c02x + c02y * c02y + c02z * c02z;
  const double n12 = c12x * c12x + c12y * c12y + c12z * c12z;
  const bool take02 = n02 > n01;
  double bx = take02 ? c02x : c01x, by = take02 ? c02y : c01y, bz = take02 ? c02z : c01z;
  double best = take02 ? n02 : n01;
  const bool take12 = n12 > best;
  bx = take12 ? c12x : bx;
  by = take12 ? c12y : by;
  bz = take12 ? c12z : bz;
  best = take12 ? n12 : best;
  // The largest row, and a vector orthogonal to it: w × e_k for the axis k where |w_k| is least.
  const double m0 = r0x * r0x + r0y * r0y + r0z * r0z;
  const double m1 = r1x * r1x + r1y * r1y + r1z * r1z;
  const double m2 = r2x * r2x + r2y * r2y + r2z * r2z;
  const bool row1 = m1 > m0;
  double wx = row1 ? r1x : r0x, wy = row1 ? r1y : r0y, wz = row1 ? r1z : r0z;
  double row = row1 ? m1 : m0;
  const bool row2 = m2 > row;
  wx = row2 ? r2x : wx;
  wy = row2 ? r2y : wy;
  wz = row2 ? r2z : wz;
  row = row2 ? m2 : row;
  const double ax = std::abs(wx), ay = std::abs(wy), az = std::abs(wz);
  const bool axis_x = ax <= ay && ax <= az;
  const bool axis_y = !axis_x && ay <= az;
  // w × e_x = (0, w_z, −w_y); w × e_y = (−w_z, 0, w_x); w × e_z = (w_y, −w_x, 0).
  double ox = axis_x ? 0.0 : (axis_y ? -wz : wy);
  double oy = axis_x ? wz : (axis_y ? 0.0 : -wx);
  double oz = axis_x ? -wy : (axis_y ? wx : 0.0);
  // Isotropic (every row zero): any direction is principal; take x.
  const bool isotropic = !(row > 0.0);
  ox = isotropic ? 1.0 : ox;
  const double on = ox * ox + oy * oy + oz * oz;
  // ε = 2.2e-16: |cross|² > ε·|row|⁴ is |cross| > √ε·|row|².
  const bool well_defined = best > 2.220446049250313e-16 * row * row;
  double x = well_defined ? bx : ox, y = well_defined ? by : oy, z = well_defined ? bz : oz;
  const double norm2 = well_defined ? best : on;
  const double inv = 1.0 / std::sqrt(norm2);
  x *= inv;
  y *= inv;
  z *= inv;
  // Sign: the component of largest magnitude is positive.
  const double px = std::abs(x), py = std::abs(y), pz = std::abs(z);
  const double lead = px >= py && px >= pz ? x : (py >= pz ? y : z);
  const double sign = lead < 0.0 ? -1.0 : 1.0;
  vx = sign * x;
  vy = sign * y;
  vz = sign * z;
}

// λ_max (and its direction) of a tensor of any magnitude: the closed forms run on the tensor
// divided by the power of two 2^e just below its largest component, so squares and cubes of
// 1e300 Pa cannot overflow nor those of 1e-300 Pa underflow. A power of two scales exactly:
// within the normal range the bits are those of the unscaled arithmetic (a repeated eigenvalue
// stays exactly repeated), and λ is scaled back exactly. 2^e and 2^−e are built from the
// exponent bits, branch-free; e is held in [−1022, 1022] so both are normal numbers.
template <bool kDirection>
inline double scaled_principal(double a, double b, double c, double d, double e, double f, double& vx, double& vy,
                               double& vz) {
  const double aa = std::abs(a), ab = std::abs(b), ac = std::abs(c);
  const double ad = std::abs(d), ae = std::abs(e), af = std::abs(f);
  double m = aa > ab ? aa : ab;
  m = ac > m ? ac : m;
  m = ad > m ? ad : m;
  m = ae > m ? ae : m;
  m = af > m ? af : m;
  constexpr std::uint64_t kExponent = 0x7FF0000000000000ULL, kLow = 1ULL << 52, kHigh = 2045ULL << 52;
  std::uint64_t bits = std::bit_cast<std::uint64_t>(m) & kExponent;
  bits = bits < kLow ? kLow : bits;
  bits = bits > kHigh ? kHigh : bits;
  const double scale = std::bit_cast<double>(bits);
  const double inv = std::bit_cast<double>(0x7FE0000000000000ULL - bits);  // 2^(1023−E) for 2^(E−1023)
  const double sa = a * inv, sb = b * inv, sc = c * inv, sd = d * inv, se = e * inv, sf = f * inv;
  const double lambda = max_principal(sa, sb, sc, sd, se, sf);
  if constexpr (kDirection) max_direction(sa, sb, sc, sd, se, sf, lambda, vx, vy, vz);
  return lambda * scale;
}

// Stress (and λ_max, and its direction) of every tet: one structure-of-arrays loop with
// unit-stride reads of gradients and writes of the outputs; the only gathers are the 12
// displacement values.
template <bool kPrincipal, bool kDirection>
void stress_kernel(const ElasticBody& body, const Eigen::VectorXd& u, StressField& stress,
                   Eigen::VectorXd* max_principal_out, Eigen::MatrixX3d* directions) {
  const TetMesh& mesh = body.mesh();
  const TetGradients& gradients = body.gradients();
  check_displacements(mesh, u);
  const int n = mesh.tet_count();
  stress.resize(n, 6);
  if constexpr (kPrincipal) max_principal_out->resize(n);
  if constexpr (kDirection) directions->resize(n, 3);
  const double lambda = body.material().lame_lambda();
  const double mu = body.material().shear_modulus();
  const int* tet = mesh.tets().data();   // column-major: node k of tet t at tet[k·n + t]
  const double* g = gradients.g.data();  // column k of tet t at g[k·n + t]
  const double* ud = u.data();
  double* s = stress.data();
  double* smax = kPrincipal ? max_principal_out->data() : nullptr;
  double* dir = kDirection ? directions->data() : nullptr;

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
    if constexpr (kPrincipal) {
      double vx = 0.0, vy = 0.0, vz = 0.0;
      smax[t] = scaled_principal<kDirection>(sxx, syy, szz, syz, sxz, sxy, vx, vy, vz);
      if constexpr (kDirection) {
        dir[t] = vx;
        dir[n + t] = vy;
        dir[2 * n + t] = vz;
      }
    }
  }
}

// λ_max of a finite stress is finite; a non-finite one means the stress itself overflowed.
void check_principal(const TetMesh* mesh, const Eigen::VectorXd& values) {
  if (values.allFinite()) return;
  for (Eigen::Index t = 0; t < values.size(); ++t) {
    if (!std::isfinite(values[t])) {
      const std::string tet = mesh ? mesh->tet_label(static_cast<int>(t)) : "tet " + std::to_string(t + 1);
      throw NumericalFailure("stress: the stress of " + tet + " overflows double precision (is the load or E absurd?)");
    }
  }
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

Eigen::MatrixXd voigt_rows_to_tensor_rows(const StressField& v) {
  Eigen::MatrixXd out(v.rows(), 9);
  // Voigt (xx, yy, zz, yz, xz, xy) → row-major (xx xy xz; yx yy yz; zx zy zz).
  const int voigt_of[9] = {0, 5, 4, 5, 1, 3, 4, 3, 2};
  for (int k = 0; k < 9; ++k) out.col(k) = v.col(voigt_of[k]);
  return out;
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

MaxPrincipal max_principal_with_direction(const Eigen::Matrix<double, 6, 1>& v) {
  MaxPrincipal out;
  out.value = scaled_principal<true>(v[0], v[1], v[2], v[3], v[4], v[5], out.direction.x(), out.direction.y(),
                                     out.direction.z());
  return out;
}

double max_principal_stress(const Eigen::Matrix<double, 6, 1>& v) {
  double x, y, z;
  return scaled_principal<false>(v[0], v[1], v[2], v[3], v[4], v[5], x, y, z);
}

StressField compute_stress(const ElasticBody& body, const Eigen::VectorXd& u) {
  StressField stress;
  stress_kernel<false, false>(body, u, stress, nullptr, nullptr);
  return stress;
}

void compute_stress_and_max_principal(const ElasticBody& body, const Eigen::VectorXd& u, StressField& stress,
                                      Eigen::VectorXd& max_principal_out) {
  stress_kernel<true, false>(body, u, stress, &max_principal_out, nullptr);
  check_principal(&body.mesh(), max_principal_out);
}

void compute_principal_stress(const ElasticBody& body, const Eigen::VectorXd& u, PrincipalStressField& out) {
  stress_kernel<true, true>(body, u, out.stress, &out.max_principal, &out.max_direction);
  check_principal(&body.mesh(), out.max_principal);
}

void max_principal_of(const StressField& stress, Eigen::VectorXd& max_principal_out, Eigen::MatrixX3d* directions) {
  const Eigen::Index n = stress.rows();
  max_principal_out.resize(n);
  const double* s = stress.data();
  double* smax = max_principal_out.data();
  if (directions) {
    directions->resize(n, 3);
    double* dir = directions->data();
#pragma GCC ivdep
    for (Eigen::Index t = 0; t < n; ++t) {
      double vx, vy, vz;
      smax[t] = scaled_principal<true>(s[t], s[n + t], s[2 * n + t], s[3 * n + t], s[4 * n + t], s[5 * n + t], vx, vy, vz);
      dir[t] = vx;
      dir[n + t] = vy;
      dir[2 * n + t] = vz;
    }
  } else {
#pragma GCC ivdep
    for (Eigen::Index t = 0; t < n; ++t) {
      double vx, vy, vz;
      smax[t] = scaled_principal<false>(s[t], s[n + t], s[2 * n + t], s[3 * n + t], s[4 * n + t], s[5 * n + t], vx, vy, vz);
    }
  }
  check_principal(nullptr, max_principal_out);
}

}  // namespace fissure
