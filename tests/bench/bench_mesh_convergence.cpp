// Time against error of the mesh resolution: the tile of bench_fem (1 × 1 × 0.05 m, corner
// supports, 10 kN on a 5 cm centre patch) solved directly at increasing tet counts and compared
// with a 200K-tet reference. Meshes differ, so the errors compare quantities every mesh defines:
//   compliance fᵀu (twice the strain energy; converges from below, the global measure),
//   the volume mean of the max principal stress over the bottom half under the centre
//   (|x|, |y| ≤ 0.1 m, z ≤ T/2: where the tile cracks first),
//   the peak max principal stress in that region, and over the whole tile (the corner supports
//   are 5 cm patches whose edges concentrate stress: that peak is not expected to converge),
//   and the stress *pattern*, on a 41 × 41 grid over the tile, each field divided by its own RMS
//   and compared in relative L2 (a uniform scale of the stress is absorbed by the fitted
//   resistance; the pattern decides where cracks go): `pattern` samples the max principal stress
//   of the tet containing each point of the plane z = T/4 (the element-scale field the stress map
//   sees), `recovered_pattern` interpolates the patch-recovered nodal stress (StressRecovery)
//   there instead, `smooth_pattern` averages the tets' values (volume-weighted) over the
//   bottom-half tets whose centroid lies within 3 cm of the point (the scale of a fragment).
// The time is meshing + assembly + factorisation + solve + stress: what a body costs the first
// time it fractures at that resolution.

#include "bench_support.hpp"

#include "fissure/fem/stress.hpp"
#include "fissure/fem/stress_recovery.hpp"

#include <Eigen/LU>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace {
using namespace fissure;

struct Measures {
  double compliance = 0.0;
  double centre_mean_stress = 0.0;
  double centre_peak_stress = 0.0;
  double global_peak_stress = 0.0;
  Eigen::VectorXd samples;         // max principal stress on the sampling grid
  Eigen::VectorXd smooth_samples;  // its 3 cm bottom-half average
  Eigen::VectorXd recovered_samples;  // the patch-recovered stress, interpolated
  int tets = 0;
};

constexpr int kGrid = 41;

// Where the kGrid² points of the plane z = T/4 (inset 1 cm from the sides) lie: the containing
// tet and the point's barycentric coordinates in it (−1e-9 slack on the containment test).
struct GridLocation {
  std::vector<int> tet = std::vector<int>(kGrid * kGrid, -1);
  std::vector<Eigen::Vector4d> barycentric = std::vector<Eigen::Vector4d>(kGrid * kGrid);
};

GridLocation locate_grid(const TetMesh& mesh) {
  GridLocation out;
  const double z = 0.0125, lo = -0.49, step = 0.98 / (kGrid - 1);
  for (int t = 0; t < mesh.tet_count(); ++t) {
    Eigen::Matrix<double, 3, 4> x;
    for (int k = 0; k < 4; ++k) x.col(k) = mesh.nodes().row(mesh.tets()(t, k)).transpose();
    if (x.row(2).minCoeff() > z || x.row(2).maxCoeff() < z) continue;
    Eigen::Matrix3d edges;
    for (int k = 0; k < 3; ++k) edges.col(k) = x.col(k + 1) - x.col(0);
    const Eigen::Matrix3d inverse = edges.inverse();
    const int i0 = std::max(0, static_cast<int>(std::ceil((x.row(0).minCoeff() - lo) / step)));
    const int i1 = std::min(kGrid - 1, static_cast<int>(std::floor((x.row(0).maxCoeff() - lo) / step)));
    const int j0 = std::max(0, static_cast<int>(std::ceil((x.row(1).minCoeff() - lo) / step)));
    const int j1 = std::min(kGrid - 1, static_cast<int>(std::floor((x.row(1).maxCoeff() - lo) / step)));
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j) {
        const Eigen::Vector3d b = inverse * (Eigen::Vector3d(lo + i * step, lo + j * step, z) - x.col(0));
        if (b.minCoeff() < -1e-9 || b.sum() > 1.0 + 1e-9) continue;
        out.tet[static_cast<std::size_t>(i * kGrid + j)] = t;
        out.barycentric[static_cast<std::size_t>(i * kGrid + j)] << 1.0 - b.sum(), b;
      }
  }
  if (std::count(out.tet.begin(), out.tet.end(), -1) > 0) throw std::runtime_error("a sampling point lies in no tet");
  return out;
}

// The raw field: each point takes its tet's max principal stress.
Eigen::VectorXd sample_raw(const GridLocation& grid, const Eigen::VectorXd& smax) {
  Eigen::VectorXd out(kGrid * kGrid);
  for (int p = 0; p < kGrid * kGrid; ++p) out[p] = smax[grid.tet[static_cast<std::size_t>(p)]];
  return out;
}

// The recovered field: the recovered nodal stress tensors interpolated linearly in the tet, then
// the max principal stress of the interpolated tensor.
Eigen::VectorXd sample_recovered(const TetMesh& mesh, const GridLocation& grid, const StressField& nodal) {
  Eigen::VectorXd out(kGrid * kGrid);
  for (int p = 0; p < kGrid * kGrid; ++p) {
    const int t = grid.tet[static_cast<std::size_t>(p)];
    Eigen::Matrix<double, 6, 1> sigma = Eigen::Matrix<double, 6, 1>::Zero();
    for (int k = 0; k < 4; ++k) sigma += grid.barycentric[static_cast<std::size_t>(p)][k] * nodal.row(mesh.tets()(t, k)).transpose();
    out[p] = max_principal_stress(sigma);
  }
  return out;
}

// Volume-weighted mean max principal stress of the bottom-half tets (centroid z < T/2) whose
// centroid lies within `radius` (in x, y) of each grid point.
Eigen::VectorXd smooth_on_grid(const TetMesh& mesh, const Eigen::VectorXd& smax, double radius) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(kGrid * kGrid), weight = Eigen::VectorXd::Zero(kGrid * kGrid);
  const double lo = -0.49, step = 0.98 / (kGrid - 1);
  for (int t = 0; t < mesh.tet_count(); ++t) {
    const Eigen::Vector3d c = mesh.centroid(t);
    if (c.z() >= 0.025) continue;
    const int i0 = std::max(0, static_cast<int>(std::ceil((c.x() - radius - lo) / step)));
    const int i1 = std::min(kGrid - 1, static_cast<int>(std::floor((c.x() + radius - lo) / step)));
    const int j0 = std::max(0, static_cast<int>(std::ceil((c.y() - radius - lo) / step)));
    const int j1 = std::min(kGrid - 1, static_cast<int>(std::floor((c.y() + radius - lo) / step)));
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j) {
        const double dx = lo + i * step - c.x(), dy = lo + j * step - c.y();
        if (dx * dx + dy * dy > radius * radius) continue;
        sum[i * kGrid + j] += mesh.volumes()[t] * smax[t];
        weight[i * kGrid + j] += mesh.volumes()[t];
      }
  }
  return sum.cwiseQuotient(weight);
}

// Relative L2 distance between two sampled fields after scaling each to unit RMS.
double pattern_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::VectorXd na = a / std::sqrt(a.squaredNorm() / a.size());
  const Eigen::VectorXd nb = b / std::sqrt(b.squaredNorm() / b.size());
  return (na - nb).norm() / nb.norm();
}

Measures solve_tile(const std::shared_ptr<const TetMesh>& mesh) {
  auto body = std::make_shared<const ElasticBody>(mesh, ElasticMaterial{});
  const Eigen::VectorXd f = bench::centre_patch(*mesh);
  const Eigen::VectorXd u = bench::centre_patch_displacement(body);
  StressField stress;
  Eigen::VectorXd smax;
  compute_stress_and_max_principal(*body, u, stress, smax);
  Measures m;
  m.tets = mesh->tet_count();
  m.compliance = f.dot(u);
  m.global_peak_stress = smax.maxCoeff();
  double volume = 0.0, integral = 0.0;
  for (int t = 0; t < mesh->tet_count(); ++t) {
    const Eigen::Vector3d c = mesh->centroid(t);
    if (std::abs(c.x()) > 0.1 || std::abs(c.y()) > 0.1 || c.z() > 0.025) continue;
    volume += mesh->volumes()[t];
    integral += mesh->volumes()[t] * smax[t];
    m.centre_peak_stress = std::max(m.centre_peak_stress, smax[t]);
  }
  m.centre_mean_stress = integral / volume;
  const GridLocation grid = locate_grid(*mesh);
  m.samples = sample_raw(grid, smax);
  m.smooth_samples = smooth_on_grid(*mesh, smax, 0.03);
  m.recovered_samples = sample_recovered(*mesh, grid, StressRecovery(*mesh).nodal(stress));
  return m;
}

const Measures& reference() {
  static const Measures r = solve_tile(bench::make_tile_mesh(200000));
  return r;
}

double percent(double value, double reference_value) { return 100.0 * (value - reference_value) / reference_value; }

void BM_MeshResolutionVsReference(benchmark::State& state) {
  const Measures& ref = reference();
  Measures m;
  for (auto _ : state) m = solve_tile(bench::make_tile_mesh(static_cast<int>(state.range(0))));
  state.counters["tets"] = m.tets;
  state.counters["reference_tets"] = ref.tets;
  state.counters["compliance_err_pct"] = percent(m.compliance, ref.compliance);
  state.counters["centre_mean_err_pct"] = percent(m.centre_mean_stress, ref.centre_mean_stress);
  state.counters["centre_peak_err_pct"] = percent(m.centre_peak_stress, ref.centre_peak_stress);
  state.counters["global_peak_err_pct"] = percent(m.global_peak_stress, ref.global_peak_stress);
  state.counters["pattern_err_pct"] = 100.0 * pattern_difference(m.samples, ref.samples);
  state.counters["recovered_pattern_err_pct"] = 100.0 * pattern_difference(m.recovered_samples, ref.recovered_samples);
  state.counters["smooth_pattern_err_pct"] = 100.0 * pattern_difference(m.smooth_samples, ref.smooth_samples);
  state.counters["centre_mean_MPa"] = m.centre_mean_stress / 1e6;
  state.counters["global_peak_MPa"] = m.global_peak_stress / 1e6;
}
BENCHMARK(BM_MeshResolutionVsReference)
    ->Arg(7000)->Arg(14000)->Arg(24000)->Arg(54000)->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
