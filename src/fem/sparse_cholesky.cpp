#include "fissure/fem/sparse_cholesky.hpp"

#include "supernodal_solve.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/huge_pages.hpp"
#include "fissure/base/thread_count.hpp"

#include <cholmod.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <mutex>
#include <new>
#include <string>

// The thread controls of the libraries CHOLMOD calls, declared weak so fem links neither: each
// call is skipped when its library is absent (another BLAS, a CHOLMOD built without OpenMP).
// blas_thread_shutdown_ ends the worker pool OpenBLAS starts when it is loaded, before main.
extern "C" void openblas_set_num_threads(int) __attribute__((weak));
extern "C" int blas_thread_shutdown_(void) __attribute__((weak));
extern "C" void omp_set_max_active_levels(int) __attribute__((weak));

namespace fissure {
namespace {

// CHOLMOD's memory on huge pages. The supernodal factor's values are tens of MB, allocated
// afresh by every factorisation and zeroed supernode by supernode: on these KVM guests each
// first-touched 4 KiB page costs ~10 µs, so touching the factor cost more than computing it
// (11.6K faults in the 24K tile's factorisation inside the eigensolve, and again on every
// factorisation, because malloc returns blocks that large to the kernel). Every SuiteSparse
// allocation goes through the function pointers of SuiteSparse_config; ours route them to base's
// allocate_huge (huge pages from 2 MiB, operator new below) behind a header holding the size,
// which release_huge needs and free() is not given. 64 bytes of header keep the blocks as aligned
// as malloc's. Where the memory lives changes no arithmetic: static solutions and modes on the
// bench tiles came out byte-identical (issue 9).
constexpr std::size_t kHeader = 64;

void* huge_malloc(std::size_t bytes) noexcept {
  if (bytes > static_cast<std::size_t>(-1) - kHeader) return nullptr;
  try {
    auto* base = static_cast<char*>(allocate_huge(bytes + kHeader));
    const std::size_t total = bytes + kHeader;
    std::memcpy(base, &total, sizeof total);
    return base + kHeader;
  } catch (const std::bad_alloc&) {
    return nullptr;  // SuiteSparse reports out-of-memory through its status
  }
}

void huge_free(void* p) noexcept {
  if (!p) return;
  char* base = static_cast<char*>(p) - kHeader;
  std::size_t total = 0;
  std::memcpy(&total, base, sizeof total);
  release_huge(base, total);
}

void* huge_calloc(std::size_t count, std::size_t size) noexcept {
  if (size != 0 && count > static_cast<std::size_t>(-1) / size) return nullptr;
  void* p = huge_malloc(count * size);
  if (p) std::memset(p, 0, count * size);
  return p;
}

void* huge_realloc(void* p, std::size_t bytes) noexcept {
  if (!p) return huge_malloc(bytes);
  std::size_t total = 0;
  std::memcpy(&total, static_cast<char*>(p) - kHeader, sizeof total);
  void* grown = huge_malloc(bytes);
  if (!grown) return nullptr;  // p stays valid, as realloc promises
  std::memcpy(grown, p, std::min(bytes, total - kHeader));
  huge_free(p);
  return grown;
}

// Before the first cholmod_start: memory from one allocator must never reach the other's free,
// and nothing in Fissure calls SuiteSparse except through this file.
void install_huge_page_allocator() {
  static std::once_flag once;
  std::call_once(once, [] {
    SuiteSparse_config.malloc_func = huge_malloc;
    SuiteSparse_config.calloc_func = huge_calloc;
    SuiteSparse_config.realloc_func = huge_realloc;
    SuiteSparse_config.free_func = huge_free;
  });
}

}  // namespace

void apply_thread_count() {
  const int n = thread_count();
  // OpenBLAS: always one thread, because its threaded dsyrk/dpotrf block differently and change
  // the factor's bits (ThreadCount test). At one thread its pool, started when the library
  // loaded, is also ended, so it adds no thread; the pool is process-wide, so this runs once per
  // change of the count.
  static std::mutex blas_mutex;
  static std::atomic<int> blas_applied{0};
  if (blas_applied.load(std::memory_order_acquire) != n) {
    std::lock_guard<std::mutex> lock(blas_mutex);
    if (blas_applied.load(std::memory_order_relaxed) != n) {
      if (openblas_set_num_threads) openblas_set_num_threads(1);
      if (n == 1 && blas_thread_shutdown_) blas_thread_shutdown_();
      blas_applied.store(n, std::memory_order_release);
    }
  }
  // OpenMP: CHOLMOD 3 (SuiteSparse 5) asks for a team of exactly 4 in its supernodal loops
  // (num_threads(4), so omp_set_num_threads and OMP_NUM_THREADS are ignored); only
  // OMP_THREAD_LIMIT, read when libgomp loads, caps that team. Zero active levels makes every
  // parallel region run on its calling thread alone. The setting belongs to the calling thread,
  // hence on every call. Counts of 2 and more leave CHOLMOD its team of 4.
  if (omp_set_max_active_levels) omp_set_max_active_levels(n == 1 ? 0 : 1);
}

struct SparseCholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  int n = 0;
  int failed_column = -1;

  Impl() {
    install_huge_page_allocator();
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    // AMD only: METIS (when present) costs more analysis time than it saves on these meshes, and
    // trying several orderings makes the analysis slower and its choice harder to predict.
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_AMD;
    common.postorder = 1;
    common.print = 0;
    common.error_handler = nullptr;
  }
  ~Impl() {
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }

  // A cholmod_sparse view of an Eigen matrix (no copy), upper triangle used.
  static cholmod_sparse view(const Eigen::SparseMatrix<double>& a) {
    cholmod_sparse s{};
    s.nrow = static_cast<std::size_t>(a.rows());
    s.ncol = static_cast<std::size_t>(a.cols());
    s.nzmax = static_cast<std::size_t>(a.nonZeros());
    s.p = const_cast<int*>(a.outerIndexPtr());
    s.i = const_cast<int*>(a.innerIndexPtr());
    s.nz = const_cast<int*>(a.innerNonZeroPtr());
    s.x = const_cast<double*>(a.valuePtr());
    s.z = nullptr;
    s.stype = 1;
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = a.isCompressed() ? 1 : 0;
    return s;
  }

  void numeric(const Eigen::SparseMatrix<double>& a) {
    cholmod_sparse s = view(a);
    cholmod_factorize(&s, factor, &common);
    if (common.status == CHOLMOD_NOT_POSDEF || factor->minor < factor->n) {
      // `minor` counts in the fill-reducing order; Perm maps it back to the caller's column.
      const std::size_t minor = factor->minor;
      failed_column = factor->Perm ? static_cast<const int*>(factor->Perm)[minor] : static_cast<int>(minor);
      throw NumericalFailure("Cholesky factorisation: the matrix is not positive definite (column " +
                             std::to_string(failed_column) + " of " + std::to_string(n) +
                             "): an unsupported body, a mechanism or a degenerate mesh");
    }
    if (common.status < CHOLMOD_OK) {
      throw NumericalFailure("Cholesky factorisation failed (CHOLMOD status " +
                             std::to_string(common.status) + ")");
    }
  }

  // Thread-safe: each call works in its own cholmod_common (status, memory counters) and its own
  // X, Y, E dense blocks, and the supernodal solve only reads the factor (cholmod_solve2 with
  // sys = CHOLMOD_A on a supernodal L calls super_lsolve/ltsolve, which read L->x and write Y,
  // E). The shared `common` is never touched, so concurrent solves on one factor do not race
  // (tested under ThreadSanitizer, docs/architecture.md). cholmod_start only sets defaults, so a
  // common per call costs nothing against the triangular solves.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const {
    // Blocks of right-hand sides: our supernodal kernel (supernodal_solve.hpp says why).
    if (b.cols() >= 2 && factor->is_super && factor->is_ll && factor->itype == CHOLMOD_INT) {
      Eigen::MatrixXd out(b.rows(), b.cols());
      supernodal_block_solve(*factor, b, out);
      return out;
    }
    apply_thread_count();
    cholmod_common local{};
    cholmod_start(&local);
    local.print = 0;
    local.error_handler = nullptr;
    cholmod_dense rhs{};
    rhs.nrow = static_cast<std::size_t>(b.rows());
    rhs.ncol = static_cast<std::size_t>(b.cols());
    rhs.nzmax = rhs.nrow * rhs.ncol;
    rhs.d = rhs.nrow;
    rhs.x = const_cast<double*>(b.data());  // read only
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    cholmod_dense *x = nullptr, *y = nullptr, *e = nullptr;
    const int ok = cholmod_solve2(CHOLMOD_A, factor, &rhs, nullptr, &x, nullptr, &y, &e, &local);
    Eigen::MatrixXd out;
    if (ok && x) out = Eigen::Map<const Eigen::MatrixXd>(static_cast<double*>(x->x), b.rows(), b.cols());
    const int status = local.status;
    cholmod_free_dense(&x, &local);
    cholmod_free_dense(&y, &local);
    cholmod_free_dense(&e, &local);
    cholmod_finish(&local);
    if (!ok) throw NumericalFailure("Cholesky solve failed (CHOLMOD status " + std::to_string(status) + ")");
    return out;
  }
};

SparseCholesky::SparseCholesky() : m_impl(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::factorize(const Eigen::SparseMatrix<double>& a) {
  if (a.rows() != a.cols()) throw InvalidInput("Cholesky factorisation: the matrix is not square");
  apply_thread_count();
  Impl& impl = *m_impl;
  if (impl.factor) cholmod_free_factor(&impl.factor, &impl.common);
  impl.n = static_cast<int>(a.rows());
  impl.failed_column = -1;
  cholmod_sparse s = Impl::view(a);
  impl.factor = cholmod_analyze(&s, &impl.common);
  if (!impl.factor) throw NumericalFailure("Cholesky analysis failed (out of memory?)");
  impl.numeric(a);
}

void SparseCholesky::refactorize(const Eigen::SparseMatrix<double>& a) {
  apply_thread_count();
  if (!m_impl->factor || a.rows() != m_impl->n) {
    factorize(a);
    return;
  }
  m_impl->numeric(a);
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) const {
  if (!m_impl->factor || b.rows() != m_impl->n) {
    throw InvalidInput("Cholesky solve: right-hand side of " + std::to_string(b.rows()) + " rows for a factor of " +
                       std::to_string(m_impl->n));
  }
  return m_impl->solve(b).col(0);
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& b) const {
  if (!m_impl->factor || b.rows() != m_impl->n) {
    throw InvalidInput("Cholesky solve: right-hand side of " + std::to_string(b.rows()) + " rows for a factor of " +
                       std::to_string(m_impl->n));
  }
  return m_impl->solve(b);
}

int SparseCholesky::rows() const { return m_impl->n; }

long sparse_cholesky_version() {
  return 1000000L * CHOLMOD_MAIN_VERSION + 1000L * CHOLMOD_SUB_VERSION + CHOLMOD_SUBSUB_VERSION;
}

int SparseCholesky::failed_column() const { return m_impl->failed_column; }

long SparseCholesky::factor_nonzeros() const {
  if (!m_impl->factor) return 0;
  // For a supernodal factor, count entries of the supernodes' lower-trapezoidal blocks.
  cholmod_factor* l = m_impl->factor;
  if (!l->is_super) {
    long nnz = 0;
    const int* colcount = static_cast<const int*>(l->ColCount);
    for (std::size_t j = 0; j < l->n; ++j) nnz += colcount[j];
    return nnz;
  }
  const int* super = static_cast<const int*>(l->super);
  const int* pi = static_cast<const int*>(l->pi);
  long nnz = 0;
  for (std::size_t s = 0; s < l->nsuper; ++s) {
    const long ncols = super[s + 1] - super[s];
    const long nrows = pi[s + 1] - pi[s];
    nnz += ncols * nrows - ncols * (ncols - 1) / 2;
  }
  return nnz;
}

}  // namespace fissure
