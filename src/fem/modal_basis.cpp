#include "fissure/fem/modal_basis.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/disk_cache.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/huge_pages.hpp"
#include "fissure/base/memory.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/fem/dof_map.hpp"
#include "fissure/fem/rigid_modes.hpp"
#include "fissure/fem/sparse_cholesky.hpp"
#include "fissure/fem/static_solver.hpp"  // StaticSolver, for the shift of bodies with many parts
#include "fissure/fem/supports.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <numbers>
#include <utility>


namespace fissure {
namespace fs = std::filesystem;
namespace {

// Progress and cancellation from inside the block iteration: every block of triangular solves
// is counted, the cancel token is checked before it and right after each report (so a sink that
// cancels is obeyed at once), and progress is reported at most every 0.2 s. The total work is
// not known in advance (restarts until convergence), so the fraction is 1 − exp(−solves/expected)
// with `expected` the solves of the first fill of the basis plus two restarts: monotone, never 1
// early.
class BlockMonitor {
public:
  BlockMonitor(ProgressSink& sink, const CancelToken* cancel, double expected_solves)
      : m_sink(sink), m_cancel(cancel), m_expected(expected_solves) {}
  void check() const {
    if (m_cancel) m_cancel->throw_if_cancelled();
  }
  void tick(Eigen::Index solves) {
    check();
    m_solves += solves;
    const auto now = std::chrono::steady_clock::now();
    if (now - m_last < std::chrono::milliseconds(200)) return;
    m_last = now;
    const double fraction = 1.0 - std::exp(-static_cast<double>(m_solves) / m_expected);
    m_sink.report("modal analysis", 0.1 + 0.85 * fraction);
    check();
  }

private:
  ProgressSink& m_sink;
  const CancelToken* m_cancel;
  double m_expected;
  long m_solves = 0;
  std::chrono::steady_clock::time_point m_last = std::chrono::steady_clock::now();
};

// Memory for the eigensolver's n-row blocks, on transparent huge pages where the kernel offers
// them (madvise mode): their first touch otherwise costs a page fault per 4 KiB, ~10 µs each on
// these KVM guests, which for the 24K tile's ~50 MB of blocks is a quarter of the whole
// eigensolve (performance.md, "Page faults"). An owner over base's allocate_huge; contents
// uninitialised (a std::vector would zero-fill the ~50 MB first).
class HugePageBuffer {
public:
  explicit HugePageBuffer(std::size_t doubles)
      : m_bytes(doubles * sizeof(double)), m_data(static_cast<double*>(allocate_huge(m_bytes))) {}
  ~HugePageBuffer() { release_huge(m_data, m_bytes); }
  HugePageBuffer(const HugePageBuffer&) = delete;
  HugePageBuffer& operator=(const HugePageBuffer&) = delete;
  double* data() const { return m_data; }

private:
  std::size_t m_bytes;
  double* m_data;
};

// A −= σ M, in A's own storage when M's pattern lies within A's, as the mass matrices' lie within
// K's (lumped M is diagonal; consistent M couples the nodes of a tet, as K does). The sparse
// expression A − σM builds a third matrix, growing it as it goes: at 24K tets its first touch was
// ~4K page faults, more than the rest of the setup (the 10 µs faults of performance.md).
void subtract_scaled(Eigen::SparseMatrix<double>& a, double sigma, const Eigen::SparseMatrix<double>& m) {
  using Inner = Eigen::SparseMatrix<double>::InnerIterator;
  const auto within = [&] {
    for (Eigen::Index j = 0; j < m.outerSize(); ++j) {
      Inner ia(a, j);
      for (Inner im(m, j); im; ++im) {
        while (ia && ia.row() < im.row()) ++ia;
        if (!ia || ia.row() != im.row()) return false;
      }
    }
    return true;
  };
  if (!a.isCompressed() || !within()) {
    a = a - sigma * m;
    return;
  }
  for (Eigen::Index j = 0; j < m.outerSize(); ++j) {
    Inner ia(a, j);
    for (Inner im(m, j); im; ++im) {
      while (ia.row() < im.row()) ++ia;
      ia.valueRef() -= sigma * im.value();
    }
  }
}

// Block shift-invert Krylov–Schur for the lowest eigenpairs of K φ = λ M φ on the M-orthogonal
// complement of the rigid motions R (M-orthonormal; empty for a supported body).
//
// The operator is T = P (K − σM)⁻¹ M with P = I − R Rᵀ M: M-self-adjoint and positive on the
// complement, its largest eigenvalues μ are the wanted λ = σ + 1/μ. R spans an invariant subspace
// of (K − σM)⁻¹ M, so working on the complement finds exactly the flexible modes and never has
// to resolve the 6k-fold zero eigenvalue (which Lanczos does poorly: with two free components a
// single-vector solver converged 11 of the 12 rigid modes).
//
// Why blocks: CHOLMOD's supernodal triangular solves cost about a fifth per column when given
// 16 right-hand sides at once instead of one (performance.md, "Eigensolve"), and the solves were
// most of the time. A block Krylov space needs more columns than a single-vector one for the
// same accuracy, but far fewer than five times as many.
//
// The iteration keeps an M-orthonormal basis V (n × k) with its images W = T V, and one pending
// block Q, M-orthogonal to V, with T V ⊂ span(V, Q) (the Krylov–Schur relation). Expanding
// appends Q, solves W_new = T Q and orthogonalises W_new against V (block classical Gram–Schmidt
// twice, full reorthogonalisation) into the next Q. When the basis is full, Rayleigh–Ritz on
// H = Vᵀ M W gives Ritz pairs (μ, y = V s) and their exact residuals T y − μ y = (W − μV) s,
// no estimate. A restart keeps the best p Ritz vectors (V S, and W S: no new solves) and the
// pending Q, which is M-orthogonal to all of the old V and so still satisfies the relation.
class BlockShiftInvert {
public:
  // Takes K (its storage becomes K − σM) and factorises it.
  BlockShiftInvert(Eigen::SparseMatrix<double> k, const Eigen::SparseMatrix<double>& m, const Eigen::MatrixXd& rigid,
                   double sigma, BlockMonitor& monitor)
      : m_m(m), m_rigid(rigid), m_mass_rigid(m * rigid), m_monitor(monitor) {
    m_rng = Rng(0x1a2c05);
    if (sigma != 0.0) subtract_scaled(k, sigma, m);
    m_factor.factorize(k);
  }

  struct Result {
    Eigen::VectorXd mu;  ///< the nev largest Ritz values of T, descending
    /// Their Ritz vectors, M-orthonormal, in the solver's own buffer (valid while it lives): a
    /// fresh n × nev matrix would be first touched 4 KiB at a time, a page fault per 512 values.
    Eigen::Map<const Eigen::MatrixXd> vectors{nullptr, 0, 0};
  };

  // `nev` pairs to `tolerance` (‖T y − μ y‖_M ≤ tolerance · μ, the criterion Spectra applied to
  // its Lanczos estimate), basis of at most `ncv` columns grown `block` at a time, at most
  // `max_restarts` restarts. Requires nev + block ≤ ncv ≤ flexible − block (room for the pending
  // block), or ncv = flexible with block 1: then the basis becomes the whole complement and the
  // first Rayleigh–Ritz is exact, so there is nothing to restart.
  Result solve(Eigen::Index nev, Eigen::Index ncv, Eigen::Index keep, Eigen::Index block, Eigen::Index flexible,
               double tolerance, int max_restarts) {
    const Eigen::Index n = m_m.rows();
    // Every n-row buffer is allocated once: V, a restart's V S (and at the end the Ritz vectors),
    // the last block's image and M X.
    m_buffer = std::make_unique<HugePageBuffer>(static_cast<std::size_t>(n) * static_cast<std::size_t>(2 * ncv + 2 * block));
    double* pv = m_buffer->data();
    double* ps = pv + n * ncv;
    using Map = Eigen::Map<Eigen::MatrixXd>;
    Map v(pv, n, ncv), scratch(ps, n, ncv), image(ps + n * ncv, n, block);
    new (&m_mx) Map(ps + n * ncv + n * block, n, block);
    m_mv.resize(n);
    Eigen::MatrixXd h = Eigen::MatrixXd::Zero(ncv, ncv);  // Vᵀ M T V, upper triangle
    Eigen::MatrixXd r = Eigen::MatrixXd::Zero(block, block);  // T V_last = V C + Q R
    Eigen::Index k = 0;
    Eigen::Index coupled = 0;  // the first column of V the next block's image couples with
    Eigen::MatrixXd q(n, block);
    for (Eigen::Index j = 0; j < block; ++j) q.col(j) = random_vector();
    orthonormalise(q, v, 0, 0, nullptr);
    for (int restart = 0;; ++restart) {
      // Expand: the Gram–Schmidt coefficients of each image are H's new columns, and the
      // coefficients R of the last image on the next block Q give the residuals below.
      while (k + block <= ncv) {
        v.middleCols(k, block) = q;
        apply(q, image);
        q = image;
        k += block;
        if (k + block <= flexible) {
          orthonormalise(q, v, k, coupled, &h);
          coupled = k - block;  // the next image couples with this block and its own
          m_mx.noalias() = m_m * image;
          r.noalias() = q.transpose() * m_mx;
        } else {  // the basis is the whole complement: T V = V H exactly
          m_mx.noalias() = m_m * image;
          h.block(0, k - block, k, block).noalias() = v.leftCols(k).transpose() * m_mx;
          r.setZero();
        }
      }
      // Rayleigh–Ritz
      m_monitor.check();
      const Eigen::MatrixXd hk = h.topLeftCorner(k, k).selfadjointView<Eigen::Upper>();
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz(hk);
      if (ritz.info() != Eigen::Success) throw NumericalFailure("modal analysis: the Rayleigh–Ritz eigensolve failed");
      // Descending μ: columns of the ascending solution, reversed.
      const Eigen::VectorXd mu = ritz.eigenvalues().reverse();
      const Eigen::MatrixXd s = ritz.eigenvectors().rowwise().reverse();
      // Residuals from the Krylov–Schur relation T V = V H + Q R E_lastᵀ: for y = V s,
      // T y − μ y = Q R s_last, and Q is M-orthonormal, so ‖T y − μ y‖_M = ‖R s_last‖ (exact
      // up to the round-off of full reorthogonalisation, not an extrapolation).
      bool converged = true;
      for (Eigen::Index j = 0; j < nev && converged; ++j) {
        converged = (r * s.block(k - block, j, block, 1)).norm() <= tolerance * mu[j];
      }
      if (converged) {
        scratch.leftCols(nev).noalias() = v.leftCols(k) * s.leftCols(nev);
        return {mu.head(nev), Eigen::Map<const Eigen::MatrixXd>(ps, n, nev)};
      }
      if (restart >= max_restarts || ncv == flexible) {
        throw NumericalFailure("modal analysis: the block eigensolver did not converge (" + std::to_string(nev) +
                               " modes, basis " + std::to_string(ncv) + ", " + std::to_string(max_restarts) +
                               " restarts)");
      }
      // Restart (thick): the best `keep` Ritz vectors, for which Vᵀ M T V is diag(μ); q stays
      // pending, and its image's Gram–Schmidt supplies the coupling to the kept vectors.
      // (Map has no swap: the maps are re-seated by placement new, as Eigen documents.)
      m_monitor.check();
      scratch.leftCols(keep).noalias() = v.leftCols(k) * s.leftCols(keep);
      std::swap(pv, ps);
      new (&v) Map(pv, n, ncv);
      new (&scratch) Map(ps, n, ncv);
      h.setZero();
      h.topLeftCorner(keep, keep) = mu.head(keep).asDiagonal();
      k = keep;
      coupled = 0;
    }
  }

private:
  // X −= R (R M)ᵀ X: the M-orthogonal projection onto the complement of the rigid motions.
  void deflate(Eigen::Ref<Eigen::MatrixXd> x) const {
    if (m_rigid.cols() > 0) x -= m_rigid * (m_mass_rigid.transpose() * x);
  }
  Eigen::VectorXd random_vector() {
    Eigen::MatrixXd x(m_m.rows(), 1);
    for (Eigen::Index i = 0; i < x.rows(); ++i) x(i, 0) = m_rng.normal();
    deflate(x);
    return x.col(0);
  }
  // out = T Q: one multi-right-hand-side solve.
  void apply(const Eigen::MatrixXd& q, Eigen::Ref<Eigen::MatrixXd> out) {
    m_monitor.tick(q.cols());
    m_mx.noalias() = m_m * q;
    out = m_factor.solve(Eigen::MatrixXd(m_mx));
    deflate(out);
  }
  // X ← an M-orthonormal basis of the part of X M-orthogonal to the first k columns of V: block
  // classical Gram–Schmidt, then modified Gram–Schmidt inside the block, twice per column. The
  // coefficients of every pass, Vᵀ M X, are summed in `h` (columns k − b … k − 1) when given. A
  // column that loses all but 1e-10 of its norm lies in the span already (the Krylov space is
  // exhausted or the block is rank deficient); it is replaced by a seeded random vector so the
  // block keeps its width.
  //
  // X is the image of V's last block, which in exact arithmetic has components only along the
  // columns from `coupled` on: the last two blocks in the block-Lanczos recurrence, everything
  // after a restart, whose kept Ritz vectors all couple to the pending block. So a first pass
  // over those columns removes what Gram–Schmidt is for, and one pass over all of V then removes
  // the rest, round-off of earlier steps; that the second removed little is checked, not assumed
  // (DGKS: Daniel, Gragg, Kaufman, Stewart 1976, the test ARPACK uses): a column that lost more than
  // 1 − 1/√2 of its M-norm in a pass gets another full pass. Before, every block took two passes
  // over all of V ("twice is enough", Giraud et al. 2005): the DGKS test spared the second for 1
  // block in 27 at 24K tets, since the first always removed the recurrence's large part. The
  // local pass halves the Gram–Schmidt, after the solves the largest cost of the iteration.
  void orthonormalise(Eigen::MatrixXd& x, const Eigen::Ref<const Eigen::MatrixXd>& v, Eigen::Index k,
                      Eigen::Index coupled, Eigen::MatrixXd* h) {
    const Eigen::Index b = x.cols();
    const auto m_norms = [&] {  // ‖x_j‖_M; leaves M X in m_mx for the next projection
      m_mx.noalias() = m_m * x;
      Eigen::VectorXd out(b);
      for (Eigen::Index j = 0; j < b; ++j) out[j] = std::sqrt(std::max(0.0, x.col(j).dot(m_mx.col(j))));
      return out;
    };
    // X −= V_[from, k) (V_[from, k)ᵀ M X), M X in m_mx; the coefficients go to h's rows from … k − 1.
    const auto project = [&](Eigen::Index from) {
      const Eigen::MatrixXd c = v.middleCols(from, k - from).transpose() * m_mx;
      if (h) h->block(from, k - b, k - from, b) += c;
      x.noalias() -= v.middleCols(from, k - from) * c;
    };
    Eigen::VectorXd entry_norm = m_norms();
    Eigen::VectorXd before = entry_norm;
    if (h && k > 0) h->block(0, k - b, k, b).setZero();
    if (coupled > 0 && k > 0) {
      project(coupled);
      before = m_norms();
    }
    for (int pass = 0; pass < 2 && k > 0; ++pass) {
      project(0);
      const Eigen::VectorXd after = m_norms();
      bool again = false;
      for (Eigen::Index j = 0; j < b; ++j) again = again || after[j] < 0.7071 * before[j];
      if (!again) break;
      before = after;
    }
    for (Eigen::Index j = 0; j < b; ++j) {
      for (int attempt = 0;; ++attempt) {
        for (int pass = 0; pass < 2 && j > 0; ++pass) {
          m_mv.noalias() = m_m * x.col(j);
          const Eigen::VectorXd c = x.leftCols(j).transpose() * m_mv;
          x.col(j).noalias() -= x.leftCols(j) * c;
        }
        m_mv.noalias() = m_m * x.col(j);
        const double norm = std::sqrt(std::max(0.0, x.col(j).dot(m_mv)));
        if (norm > 1e-10 * entry_norm[j] && norm > 0.0) {
          x.col(j) /= norm;
          break;
        }
        if (attempt >= 3) throw NumericalFailure("modal analysis: the block Krylov basis cannot be extended");
        // Replace by a random vector, made M-orthogonal to V like the others.
        Eigen::MatrixXd r = random_vector();
        for (int pass = 0; pass < 2 && k > 0; ++pass) {
          const Eigen::MatrixXd mr = m_m * r;
          r.noalias() -= v.leftCols(k) * (v.leftCols(k).transpose() * mr);
        }
        x.col(j) = r.col(0);
        m_mv.noalias() = m_m * x.col(j);
        entry_norm[j] = std::sqrt(std::max(0.0, x.col(j).dot(m_mv)));
      }
    }
  }

  const Eigen::SparseMatrix<double>& m_m;
  const Eigen::MatrixXd& m_rigid;
  Eigen::MatrixXd m_mass_rigid;
  SparseCholesky m_factor;
  BlockMonitor& m_monitor;
  Rng m_rng{0x1a2c05};
  std::unique_ptr<HugePageBuffer> m_buffer;  // V, a restart's V S (and the result), the last image, M X
  Eigen::Map<Eigen::MatrixXd> m_mx{nullptr, 0, 0};  // M X for one block, in m_buffer
  Eigen::VectorXd m_mv;  // M x for one column
};

// An upper bound of the first flexible eigenvalue of a free body, for the shift. Rayleigh–Ritz
// over the 18 quadratic displacement fields of each component (every component × every
// quadratic monomial of the centred, size-scaled coordinates), with the rigid motions projected
// out: any vector M-orthogonal to them has a Rayleigh quotient ≥ λ₇, so the smallest Ritz value
// is a bound, and quadratic fields contain the bending and twisting shapes of beams and plates
// well enough to land within a small factor of λ₇. Costs 18 K-products per component instead
// of a factorisation. Bodies with many parts fall back to two steps of inverse iteration.
double first_flexible_eigenvalue_bound(std::shared_ptr<const ElasticBody> body, MassKind mass,
                                       const Eigen::MatrixXd& rigid) {
  const TetMesh& mesh = body->mesh();
  const Eigen::Index dofs = body->stiffness().rows();
  if (mesh.component_count() > 16) {
    StaticSolverOptions options;
    options.mass = mass;
    const StaticSolver solver(body, {}, options);
    Rng rng(0x5eed);
    Eigen::VectorXd u(dofs);
    for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = rng.normal();
    for (int step = 0; step < 2; ++step) {
      u = solver.solve(body->mass_times(mass, u)).displacement;
      u /= u.norm();
    }
    return u.dot(body->stiffness() * u) / u.dot(body->mass_times(mass, u));
  }
  const auto groups = nodes_by_component(mesh);
  double bound = INFINITY;
  for (const auto& nodes : groups) {
    const NodeFrame frame = node_frame(mesh, nodes);
    const Eigen::Vector3d& centre = frame.centroid;
    const double size = frame.size;
    Eigen::MatrixXd v = Eigen::MatrixXd::Zero(dofs, 18);
    for (int node : nodes) {
      const Eigen::Vector3d p = (mesh.nodes().row(node).transpose() - centre) / size;
      const double monomial[6] = {p.x() * p.x(), p.y() * p.y(), p.z() * p.z(), p.x() * p.y(), p.y() * p.z(), p.x() * p.z()};
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 6; ++k) v(3 * node + c, 6 * c + k) = monomial[k];
    }
    Eigen::MatrixXd mv(dofs, 18), kv(dofs, 18);
    for (int j = 0; j < 18; ++j) {
      v.col(j) -= rigid * (rigid.transpose() * body->mass_times(mass, v.col(j)));
      mv.col(j) = body->mass_times(mass, v.col(j));
      kv.col(j) = body->stiffness() * v.col(j);
    }
    const Eigen::MatrixXd mr = v.transpose() * mv, kr = v.transpose() * kv;
    // M-orthonormalise the trial space, dropping directions with (numerically) no mass.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> mass_eigen(mr);
    const double top = mass_eigen.eigenvalues().maxCoeff();
    std::vector<int> keep;
    for (int j = 0; j < 18; ++j)
      if (mass_eigen.eigenvalues()[j] > 1e-10 * top) keep.push_back(j);
    Eigen::MatrixXd basis(18, static_cast<Eigen::Index>(keep.size()));
    for (std::size_t j = 0; j < keep.size(); ++j) {
      basis.col(static_cast<Eigen::Index>(j)) = mass_eigen.eigenvectors().col(keep[j]) / std::sqrt(mass_eigen.eigenvalues()[keep[j]]);
    }
    const Eigen::MatrixXd reduced = basis.transpose() * kr * basis;
    bound = std::min(bound, Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(reduced).eigenvalues().minCoeff());
  }
  return bound;
}

}  // namespace

double modal_memory_estimate(Eigen::Index dofs, Eigen::Index modes, Eigen::Index krylov_size, Eigen::Index stiffness_nonzeros) {
  const double n = static_cast<double>(dofs), m = static_cast<double>(modes), ncv = static_cast<double>(krylov_size);
  // Φ twice (the Ritz vectors, now formed in the restart copy, so an overestimate by n·m, and the
  // expanded copy), the block basis V and a restart's copy
  // V S (the block image and M X: 2·b columns, counted in the third n × ncv), the dense
  // ncv × ncv Rayleigh–Ritz matrix with its eigenvectors and a copy, and the factor of K − σM:
  // nnz(L) = 4.7 × nnz(K_ff) on the 21.5K-tet CGAL tile (2.88M against 608K, bench_fem's
  // nnz_L), 38 bytes per nnz(K) in values, counted as 48 with the supernodal indices and
  // CHOLMOD's workspace.
  return 8.0 * (2.0 * n * m + 3.0 * n * ncv + 3.0 * ncv * ncv) + 48.0 * static_cast<double>(stiffness_nonzeros);
}

namespace {

void write_pod(std::string& out, const void* data, std::size_t bytes) {
  if (bytes == 0) return;  // an empty array's data() may be null
  out.append(static_cast<const char*>(data), bytes);
}

}  // namespace

std::vector<std::string> ModalOptions::problems() const {
  std::vector<std::string> out;
  if (mode_count < 1 || mode_count > 5000) out.push_back("mode count " + std::to_string(mode_count) + " is outside [1, 5000]");
  if (!(tolerance > 0.0 && tolerance < 1e-2)) out.push_back("tolerance " + format_number(tolerance) + " is outside (0, 0.01)");
  if (max_iterations < 1) out.push_back("max_iterations must be >= 1");
  if (krylov_size < 0) out.push_back("krylov_size must be >= 0");
  return out;
}

void ModalOptions::validate() const { throw_if_problems("modal analysis", problems()); }

ModalBasis ModalBasis::compute(std::shared_ptr<const ElasticBody> body, const std::vector<int>& fixed_dofs,
                               const ModalOptions& options, ProgressSink* progress, const CancelToken* cancel) {
  options.validate();
  const TetMesh& mesh = body->mesh();
  check_supports_for_mechanisms(mesh, fixed_dofs);
  NullProgress null_progress;
  ProgressSink& sink = progress ? *progress : null_progress;
  if (cancel) cancel->throw_if_cancelled();
  sink.report("modal analysis", 0.0);

  const bool free = fixed_dofs.empty();
  const DofMap dofs(3 * mesh.node_count(), fixed_dofs);
  Eigen::SparseMatrix<double> k = dofs.restrict_matrix(body->stiffness());
  const Eigen::SparseMatrix<double> m = dofs.restrict_matrix(body->mass_matrix(options.mass));
  // Free body: the exact rigid motions, M-orthonormal (no dof is fixed, so free = all dofs).
  const Eigen::MatrixXd rigid = free ? mass_orthonormal_rigid_modes(*body, options.mass) : Eigen::MatrixXd();
  const Eigen::Index n = k.rows();
  const Eigen::Index nev = options.mode_count;
  if (nev + rigid.cols() >= n) {
    throw InvalidInput("modal analysis: " + std::to_string(options.mode_count) + " modes asked for, but the mesh has only " +
                       std::to_string(n - rigid.cols()) + " flexible degrees of freedom");
  }
  // Block of 8 right-hand sides, basis of 3·nev, restarts keeping nev + (ncv − nev)/4: the
  // fastest of the block sizes 8–32, bases 2–5·nev and keep fractions 0.15–0.4 tried at 24K
  // tets, m = 50 (larger blocks solve cheaper per column but need more columns and more
  // Gram–Schmidt). Beyond nev = 80 the basis grows by 160 only: Gram–Schmidt costs n·ncv² and
  // Rayleigh–Ritz ncv³ per restart, and 3·nev made m = 400 slower than single-vector Lanczos
  // (nev + 160 halved it). Blocks of 4 for few modes on small meshes: a solve costs about the
  // same for 4 columns as for 8 (BM_BlockSolve), but a block of 4 converges 20 modes in fewer
  // columns and half the Gram–Schmidt, which on a small mesh costs as much as the solves
  // (n·k per column against nnz(L) ~ n^1.7): 7K tets, m = 10 and 20, 8 → 4 took 92–99 → 73–90 ms,
  // while at 24K it was even or slower. Smaller blocks still for tiny meshes, whose free
  // dimension must hold the basis plus a pending block.
  const Eigen::Index flexible = n - rigid.cols();
  const Eigen::Index widest = nev <= 24 && n <= 12000 ? 4 : 8;
  Eigen::Index block = std::clamp<Eigen::Index>((flexible - nev) / 3, 1, widest);
  Eigen::Index ncv = std::min<Eigen::Index>(
      flexible - block, std::max<Eigen::Index>(options.krylov_size > 0 ? options.krylov_size : nev + std::min<Eigen::Index>(2 * nev, 160), nev + 3 * block));
  if (ncv < nev + block) {
    // Nearly every flexible mode wanted (tiny meshes): one vector at a time over the whole
    // complement, where the first Rayleigh–Ritz is exact.
    block = 1;
    ncv = flexible;
  }
  // Refuse what cannot fit before any factorisation (`modes --count 5000` on a large mesh).
  require_memory(modal_memory_estimate(n, nev, ncv, k.nonZeros()), options.memory_limit_bytes,
                 "modal analysis of " + std::to_string(nev) + " modes (" + std::to_string(n) + " dofs)");

  // Shift-invert about σ: 0 for a supported body (K_ff is positive definite), slightly below
  // zero for a free one so that K − σM is positive definite.
  const double sigma = free ? -0.01 * first_flexible_eigenvalue_bound(body, options.mass, rigid) : 0.0;
  if (cancel) cancel->throw_if_cancelled();

  sink.report("modal analysis", 0.02);
  const Eigen::Index keep = std::min(ncv - block, nev + (ncv - nev) / 4);
  BlockMonitor monitor(sink, cancel, static_cast<double>(ncv + 2 * (ncv - keep)));
  BlockShiftInvert solver(std::move(k), m, rigid, sigma, monitor);  // factorises K − σM
  const BlockShiftInvert::Result ritz = solver.solve(nev, ncv, keep, block, flexible, options.tolerance, options.max_iterations);
  if (cancel) cancel->throw_if_cancelled();
  // μ descending is λ = σ + 1/μ ascending.
  const Eigen::VectorXd values = (sigma + ritz.mu.array().inverse()).matrix();
  const Eigen::Map<const Eigen::MatrixXd>& vectors = ritz.vectors;  // in the solver's buffer

  ModalBasis basis;
  basis.m_mass = options.mass;
  basis.m_eigenvalues = values;
  basis.m_modes.resize(3 * static_cast<Eigen::Index>(mesh.node_count()), nev);
  for (Eigen::Index j = 0; j < nev; ++j) basis.m_modes.col(j) = dofs.expand_vector(vectors.col(j));

  if (free) {
    basis.m_rigid_modes = rigid;
    // The rigid modes' eigenvalues are their Rayleigh quotients rᵀKr (rᵀMr = 1): round-off of
    // K's null space. Exactly 6 per component must be near zero: they are (K R ≈ 0), and the
    // first flexible eigenvalue of the complement must be clearly positive, or the body has a
    // further zero-energy motion (a hinge between parts touching at a node or an edge).
    basis.m_rigid_eigenvalues = (rigid.transpose() * (body->stiffness() * rigid)).diagonal();
    const double first_flexible = values[0];
    // Rigid Rayleigh quotients are ~1e-13·λ₇ (fem-pitfalls §2.7); 1e-6·λ₇ leaves seven decades.
    for (Eigen::Index i = 0; i < basis.m_rigid_eigenvalues.size(); ++i) {
      if (!(std::abs(basis.m_rigid_eigenvalues[i]) <= 1e-6 * first_flexible)) {
        throw NumericalFailure("modal analysis: rigid motion " + std::to_string(i) + " has energy " +
                               format_number(basis.m_rigid_eigenvalues[i]) + " against a first flexible eigenvalue of " +
                               format_number(first_flexible) + ": the body is not free, or has a further zero-energy motion");
      }
    }
  }
  if (!basis.m_eigenvalues.allFinite() || !basis.m_modes.allFinite() || !(basis.m_eigenvalues[0] > 0.0)) {
    throw NumericalFailure("modal analysis: non-finite or non-positive flexible eigenvalues");
  }
  sink.report("modal analysis", 1.0);
  return basis;
}

Eigen::VectorXd ModalBasis::frequencies_hz() const {
  return m_eigenvalues.array().sqrt() / (2.0 * std::numbers::pi);
}

Eigen::VectorXd ModalBasis::static_displacement(const Eigen::VectorXd& f, ModalPrecision precision) const {
  if (m_eigenvalues.size() == 0 || !m_single) throw InvalidInput("modal solve: the basis holds no modes");
  if (f.size() != m_modes.rows()) {
    throw InvalidInput("modal solve: load vector has " + std::to_string(f.size()) + " entries, the basis has " +
                       std::to_string(m_modes.rows()) + " dofs");
  }
  if (!f.allFinite()) {
    Eigen::Index i = 0;
    while (std::isfinite(f[i])) ++i;
    throw InvalidInput("modal solve: the load is not finite (component " + std::string(1, "xyz"[i % 3]) + " of node " +
                       std::to_string(i / 3 + 1) + " in the mesh's order)");
  }
  // Loads are patches: only the rows of Φ under non-zero forces contribute to Φᵀf, so reading
  // those rows instead of all of Φ halves the memory traffic (Φ is 6.7 MB at 24K tets, m = 50).
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m_modes.cols());
  Eigen::Index nonzeros = 0;
  for (Eigen::Index i = 0; i < f.size(); ++i) nonzeros += f[i] != 0.0;
  if (nonzeros * 4 < f.size()) {
    for (Eigen::Index i = 0; i < f.size(); ++i) {
      if (f[i] != 0.0) q.noalias() += f[i] * m_modes.row(i).transpose();
    }
  } else {
    q.noalias() = m_modes.transpose() * f;
  }
  q.array() /= m_eigenvalues.array();
  if (precision == ModalPrecision::Double) return m_modes * q;
  // Each u_i sums m products of float terms: relative error ≲ m·2⁻²⁴ ≈ 3e-6 at m = 50.
  std::call_once(m_single->made, [this] { m_single->modes = m_modes.cast<float>(); });
  const Eigen::VectorXf u = m_single->modes * q.cast<float>();
  return u.cast<double>();
}

Hash128 ModalBasis::cache_key(const ElasticBody& body, const std::vector<int>& fixed_dofs, const ModalOptions& options) {
  ContentHasher h;
  h.add("fissure modal basis").add(std::int64_t{kFormatVersion});
  h.add(body.mesh().nodes()).add(Eigen::MatrixXi(body.mesh().tets()));
  h.add(body.material().youngs_modulus).add(body.material().poisson_ratio).add(body.material().density);
  std::vector<int> fixed = fixed_dofs;
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  h.add_bytes(fixed.data(), fixed.size() * sizeof(int));
  h.add(std::int64_t{options.mode_count}).add(std::int64_t{options.mass == MassKind::Lumped ? 0 : 1});
  h.add(options.tolerance).add(std::int64_t{options.krylov_size});
  return h.finish();
}

void ModalBasis::save(const fs::path& path, const Hash128& key) const {
  std::string out;
  out.append("FISSMODE");
  const std::int64_t header[6] = {kFormatVersion, static_cast<std::int64_t>(m_modes.rows()),
                                  static_cast<std::int64_t>(m_modes.cols()),
                                  static_cast<std::int64_t>(m_rigid_modes.cols()),
                                  m_mass == MassKind::Lumped ? 0 : 1, 0};
  write_pod(out, header, sizeof header);
  write_pod(out, &key.hi, 8);
  write_pod(out, &key.lo, 8);
  write_pod(out, m_eigenvalues.data(), sizeof(double) * static_cast<std::size_t>(m_eigenvalues.size()));
  write_pod(out, m_rigid_eigenvalues.data(), sizeof(double) * static_cast<std::size_t>(m_rigid_eigenvalues.size()));
  write_pod(out, m_modes.data(), sizeof(double) * static_cast<std::size_t>(m_modes.size()));
  write_pod(out, m_rigid_modes.data(), sizeof(double) * static_cast<std::size_t>(m_rigid_modes.size()));
  // A checksum of everything before it: a file altered on disk (finite but wrong values, which
  // once gave a max |u| 11× off without a word) is refused on load.
  const Hash128 checksum = ContentHasher().add_bytes(out.data(), out.size()).finish();
  write_pod(out, &checksum.hi, 8);
  write_pod(out, &checksum.lo, 8);
  write_file_atomically(path, out);
}

ModalBasis ModalBasis::load(const fs::path& path, const Hash128& expected_key) {
  const std::string file_bytes = read_file(path);
  const std::string name = path.string();
  if (file_bytes.size() < 16) throw IoError(name + ": modal basis file is truncated");
  const std::string_view bytes(file_bytes.data(), file_bytes.size() - 16);
  std::size_t pos = 0;
  auto take = [&](void* dst, std::size_t size) {
    if (pos + size > bytes.size()) throw IoError(name + ": modal basis file is truncated");
    if (size == 0) return;  // an empty array's data() may be null, which memcpy must not see
    std::memcpy(dst, bytes.data() + pos, size);
    pos += size;
  };
  char magic[8];
  take(magic, 8);
  if (std::memcmp(magic, "FISSMODE", 8) != 0) throw IoError(name + ": not a Fissure modal basis file");
  std::int64_t header[6];
  take(header, sizeof header);
  if (header[0] != kFormatVersion) {
    throw IoError(name + ": modal basis format version " + std::to_string(header[0]) + ", expected " +
                  std::to_string(kFormatVersion));
  }
  Hash128 key;
  take(&key.hi, 8);
  take(&key.lo, 8);
  if (!(key == expected_key)) throw IoError(name + ": modal basis belongs to another body or options");
  Hash128 stored;
  std::memcpy(&stored.hi, file_bytes.data() + bytes.size(), 8);
  std::memcpy(&stored.lo, file_bytes.data() + bytes.size() + 8, 8);
  if (!(ContentHasher().add_bytes(bytes.data(), bytes.size()).finish() == stored)) {
    throw IoError(name + ": modal basis file is damaged or truncated (checksum mismatch)");
  }
  const std::int64_t rows = header[1], m = header[2], rigid = header[3];
  if (rows <= 0 || m <= 0 || rigid < 0 || rows > (1LL << 31) || m > 100000 || rigid > rows ||
      8.0 * static_cast<double>(m + rigid + rows * (m + rigid)) != static_cast<double>(bytes.size() - pos)) {
    throw IoError(name + ": modal basis header is corrupt");
  }
  ModalBasis basis;
  basis.m_mass = header[4] == 0 ? MassKind::Lumped : MassKind::Consistent;
  basis.m_eigenvalues.resize(m);
  basis.m_rigid_eigenvalues.resize(rigid);
  basis.m_modes.resize(rows, m);
  basis.m_rigid_modes.resize(rigid > 0 ? rows : 0, rigid);
  take(basis.m_eigenvalues.data(), sizeof(double) * static_cast<std::size_t>(m));
  take(basis.m_rigid_eigenvalues.data(), sizeof(double) * static_cast<std::size_t>(rigid));
  take(basis.m_modes.data(), sizeof(double) * static_cast<std::size_t>(rows * m));
  take(basis.m_rigid_modes.data(), sizeof(double) * static_cast<std::size_t>(basis.m_rigid_modes.size()));
  if (pos != bytes.size()) throw IoError(name + ": modal basis file has trailing bytes");
  if (!basis.m_eigenvalues.allFinite() || !basis.m_modes.allFinite() || !basis.m_rigid_modes.allFinite()) {
    throw IoError(name + ": modal basis holds non-finite numbers");
  }
  return basis;
}

ModalBasis cached_modal_basis(std::shared_ptr<const ElasticBody> body, const std::vector<int>& fixed_dofs,
                              const ModalOptions& options, const fs::path& cache_dir, bool* loaded,
                              ProgressSink* progress, const CancelToken* cancel, std::string* cache_warning) {
  const Hash128 key = ModalBasis::cache_key(*body, fixed_dofs, options);
  const fs::path file = cache_dir / ("modes-" + key.hex() + ".bin");
  if (loaded) *loaded = false;
  if (cache_warning) cache_warning->clear();
  std::error_code ec;
  if (fs::exists(file, ec)) {
    try {
      ModalBasis basis = ModalBasis::load(file, key);
      fs::last_write_time(file, fs::file_time_type::clock::now(), ec);  // used now (disk_cache.hpp's LRU)
      if (loaded) *loaded = true;
      return basis;
    } catch (const IoError&) {
      // A damaged or foreign cache file is recomputed and overwritten below.
    }
  }
  ModalBasis basis = ModalBasis::compute(std::move(body), fixed_dofs, options, progress, cancel);
  // Caching is an optimisation: an unwritable cache directory must not fail the analysis, but
  // the caller is told, so a user whose every run recomputes knows why.
  std::string problem;
  fs::create_directories(cache_dir, ec);
  if (ec) {
    problem = "cannot create " + cache_dir.string() + ": " + ec.message();
  } else {
    try {
      basis.save(file, key);
      prune_cache(cache_dir, default_cache_size_limit(), file.filename().string());
    } catch (const IoError& e) {
      problem = e.what();
    }
  }
  if (!problem.empty() && cache_warning) {
    *cache_warning = "modal basis not cached (" + problem + "); it will be computed again next time";
  }
  return basis;
}

}  // namespace fissure
