#pragma once
/// Sparse Cholesky factorisation of a symmetric positive definite matrix with CHOLMOD's
/// supernodal LLᵀ (4–6× faster than Eigen's simplicial solvers at 24K–54K tets, performance.md
/// §3). CHOLMOD stays inside the implementation.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>

namespace fissure {

class SparseCholesky {
public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  /// Analyses (AMD ordering) and factorises `a`. Only the upper triangle of `a` is read. Throws
  /// NumericalFailure naming the first failing column when `a` is not positive definite, and
  /// InvalidInput when `a` is not square. O(nnz(L)) memory.
  void factorize(const Eigen::SparseMatrix<double>& a);
  /// Re-factorises a matrix with the same pattern as the last one, reusing the analysis.
  void refactorize(const Eigen::SparseMatrix<double>& a);

  /// x = A⁻¹ b for one or several right-hand sides (columns). Throws InvalidInput when nothing is
  /// factorised or b has the wrong row count. One column is CHOLMOD's supernodal solve; two or
  /// more go through Fissure's own supernodal kernel, 2–3× faster per column for blocks of 8
  /// (BM_BlockSolve in docs/BENCHMARKS.md), equal to CHOLMOD's to round-off. Thread-safe:
  /// concurrent solves on one factor each use their own workspace and only read the factor
  /// (factorize/refactorize, being non-const, must not run at the same time).
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const;

  int rows() const;
  /// After a failed factorisation: the column (in the caller's numbering) whose pivot was not
  /// positive; −1 otherwise.
  int failed_column() const;
  /// Non-zeros of the factor L.
  long factor_nonzeros() const;

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// The CHOLMOD version the library was built against (major·10⁶ + minor·10³ + patch): caches of
/// solved fields key on it, since another factorisation rounds differently.
long sparse_cholesky_version();

/// Holds the libraries CHOLMOD calls to fissure::thread_count() (base/thread_count.hpp): at one
/// thread, OpenBLAS's worker pool is ended and CHOLMOD's OpenMP regions run on the calling thread,
/// so the process adds no thread. At two or more CHOLMOD keeps its fixed OpenMP team of 4
/// (OMP_THREAD_LIMIT, set before start, caps it) and OpenBLAS stays at one thread, since its
/// threaded kernels change the factor's bits. Results are identical at any count. Called by every
/// factorisation and solve; cheap and safe to call from any thread.
void apply_thread_count();

}  // namespace fissure
