// Issue 9: one thread count, honoured by every library Fissure calls. Before, CHOLMOD's
// supernodal factorisation started a team of 4 OpenMP threads (its loops ask for num_threads(4),
// which OMP_NUM_THREADS does not override) and OpenBLAS's pthread build started its worker pool
// when it was loaded, so a "single-threaded" run had 4–5 threads in /proc/self/task.

#include "fissure/base/error.hpp"
#include "fissure/base/thread_count.hpp"
#include "fissure/fem/modal_basis.hpp"
#include "fissure/fem/sparse_cholesky.hpp"
#include "fissure/fem/supports.hpp"
#include "fissure/fem/dof_map.hpp"

#include "fem_test_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace fissure {
namespace {

int task_count() {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) ++n;
  return n;
}

// Samples the process's threads while Lanczos runs (the progress sink is called from inside the
// eigensolve, between shift-invert solves).
class TaskSampler final : public ProgressSink {
 public:
  void report(std::string_view, double) override { max_tasks = std::max(max_tasks, task_count()); }
  int max_tasks = 0;
};

// Restores the thread count a test changed.
class ThreadCountGuard {
 public:
  ThreadCountGuard() : m_saved(thread_count()) {}
  ~ThreadCountGuard() { set_thread_count(m_saved); }

 private:
  int m_saved;
};

// 24K tets: large enough that CHOLMOD's supernodal loops go parallel (they did at this size).
struct Problem {
  std::shared_ptr<const ElasticBody> body;
  std::vector<int> fixed;
  Eigen::SparseMatrix<double> k;
};

Problem problem(int n) {
  Problem p;
  p.body = std::make_shared<const ElasticBody>(test::box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), n, n, n),
                                               test::concrete());
  p.fixed = resolve_supports(p.body->mesh(), {parse_support("zmin")});
  p.k = DofMap(p.body->stiffness().rows(), p.fixed).restrict_matrix(p.body->stiffness());
  return p;
}

// The largest number of threads seen during and after a factorisation and a 10-mode eigensolve.
// libgomp and OpenBLAS keep their workers alive after a call returns, so a count taken afterwards
// also sees every worker started during the call.
int max_tasks_at_one_thread() {
  set_thread_count(1);
  const Problem p = problem(16);
  SparseCholesky chol;
  chol.factorize(p.k);
  int most = task_count();
  TaskSampler sampler;
  ModalOptions options;
  options.mode_count = 10;
  ModalBasis::compute(p.body, p.fixed, options, &sampler);
  return std::max({most, sampler.max_tasks, task_count()});
}

// In a fresh process (gtest re-executes the binary for this one test), so no earlier test has
// left a worker pool behind and OpenBLAS starts its pool at load time as in every command.
TEST(ThreadCount, OneThreadMeansOneThreadDuringFactorisationAndEigensolve) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(std::exit(max_tasks_at_one_thread()), testing::ExitedWithCode(1), "")
      << "the exit code is the largest number of threads in /proc/self/task";
}

// The control that shows the sampler can fail: at two threads CHOLMOD's team of 4 appears
// (unless OMP_THREAD_LIMIT capped it when the process started).
TEST(ThreadCount, TwoThreadsStartWorkers) {
  if (std::getenv("OMP_THREAD_LIMIT")) GTEST_SKIP() << "OMP_THREAD_LIMIT caps CHOLMOD's team";
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        set_thread_count(2);
        const Problem p = problem(16);
        SparseCholesky chol;
        chol.factorize(p.k);
        std::exit(task_count() > 1 ? 0 : 1);
      },
      testing::ExitedWithCode(0), "");
}

bool same_bytes(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(ThreadCount, ResultsAreBitIdenticalAtOneAndTwoThreads) {
  const ThreadCountGuard guard;
  const Problem p = problem(16);
  Eigen::MatrixXd rhs(p.k.rows(), 16);
  Rng rng(9);
  for (Eigen::Index i = 0; i < rhs.size(); ++i) rhs.data()[i] = rng.uniform(-1.0, 1.0);
  const Problem small = problem(8);
  ModalOptions options;
  options.mode_count = 10;

  Eigen::MatrixXd x[2];
  ModalBasis basis[2];
  for (int threads : {1, 2}) {
    set_thread_count(threads);
    SparseCholesky chol;
    chol.factorize(p.k);
    x[threads - 1] = chol.solve(rhs);
    basis[threads - 1] = ModalBasis::compute(small.body, small.fixed, options);
  }
  EXPECT_TRUE(same_bytes(x[0], x[1]));
  EXPECT_TRUE(same_bytes(basis[0].eigenvalues(), basis[1].eigenvalues()));
  EXPECT_TRUE(same_bytes(basis[0].modes(), basis[1].modes()));
}

TEST(ThreadCount, RefusesCountsOutsideItsRange) {
  const ThreadCountGuard guard;
  EXPECT_THROW(set_thread_count(0), InvalidInput);
  EXPECT_THROW(set_thread_count(1025), InvalidInput);
  set_thread_count(3);
  EXPECT_EQ(thread_count(), 3);
}

}  // namespace
}  // namespace fissure
