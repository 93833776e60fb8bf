// Issue 8: the fit will run trials on one shared body from several threads. Every const method
// of ElasticBody, StaticSolver, SparseCholesky, ModalBasis and StressRecovery must be safe to
// call concurrently. Before: ElasticBody::mass_matrix filled mutable caches unguarded, and
// SparseCholesky::solve wrote CHOLMOD's shared cholmod_common (status, workspace), so
// concurrent solves raced (ThreadSanitizer reports on main; docs/architecture.md records the
// run of this test under -DFISSURE_SANITIZE=thread).
//
// Four threads run many static solves (supported, and free with the consistent mass, whose
// first use builds it lazily under contention), stress evaluations raw and recovered, and modal
// solves in both precisions (the first single-precision solve makes the float copy of Φ), all on
// objects shared between them, touched for the first time inside the threads. Each result goes
// to its own slot; afterwards the same work is done serially, and every result must be the
// same bytes.

#include "fissure/fem/load.hpp"
#include "fissure/fem/modal_basis.hpp"
#include "fissure/fem/static_solver.hpp"
#include "fissure/fem/stress.hpp"
#include "fissure/fem/stress_recovery.hpp"

#include "fem_test_meshes.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <thread>

namespace fissure {
namespace {

struct Results {
  Eigen::VectorXd supported, free_body, modal_double, modal_single;
  Eigen::VectorXd max_principal, recovered_max_principal;
  Eigen::MatrixX3d direction, recovered_direction;
  StressField stress;
};

bool same_bytes(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(ThreadSafety, SharedBodySolvesAndStressesGiveTheSerialBytes) {
  auto mesh = test::perturbed_box(5, 0.2, 21);
  auto body = std::make_shared<const ElasticBody>(mesh, test::concrete());
  const std::vector<int> supports = resolve_supports(*mesh, {parse_support("zmin")});
  const StaticSolver supported(body, supports);
  StaticSolverOptions consistent;
  consistent.mass = MassKind::Consistent;
  const StaticSolver free_solver(body, {}, consistent);  // the consistent M is built in the threads
  ModalOptions options;
  options.mode_count = 12;
  const ModalBasis basis = ModalBasis::compute(body, supports, options);  // float copy made in the threads
  const StressRecovery recovery(*mesh);

  // Distinct loads: a patch on the top face moved and turned per task.
  constexpr int kThreads = 4, kTasksPerThread = 12, kTasks = kThreads * kTasksPerThread;
  std::vector<Eigen::VectorXd> loads(kTasks);
  for (int k = 0; k < kTasks; ++k) {
    const double x = 0.2 + 0.6 * (k % 7) / 6.0, y = 0.2 + 0.6 * (k % 5) / 4.0;
    loads[k] = assemble_load(*mesh, parse_load("ball:" + std::to_string(x) + "," + std::to_string(y) + ",1,0.3=" +
                                               std::to_string(100 * k) + ",-50,-1e4"));
  }
  auto run = [&](int k) {
    Results r;
    const Eigen::VectorXd& f = loads[k];
    r.supported = supported.solve(f).displacement;
    r.free_body = free_solver.solve(f).displacement;
    r.modal_double = basis.static_displacement(f, ModalPrecision::Double);
    r.modal_single = basis.static_displacement(f, ModalPrecision::Single);
    PrincipalStressField raw, recovered;
    compute_principal_stress(*body, r.supported, raw);
    compute_principal_stress(*body, r.supported, recovery, recovered);
    r.stress = raw.stress;
    r.max_principal = raw.max_principal;
    r.direction = raw.max_direction;
    r.recovered_max_principal = recovered.max_principal;
    r.recovered_direction = recovered.max_direction;
    return r;
  };

  std::vector<Results> threaded(kTasks);
  std::vector<std::thread> workers;
  for (int w = 0; w < kThreads; ++w) {
    workers.emplace_back([&, w] {
      for (int i = 0; i < kTasksPerThread; ++i) threaded[w + kThreads * i] = run(w + kThreads * i);
    });
  }
  for (std::thread& t : workers) t.join();

  for (int k = 0; k < kTasks; ++k) {
    const Results serial = run(k);
    const Results& t = threaded[k];
    ASSERT_TRUE(same_bytes(t.supported, serial.supported)) << "task " << k;
    ASSERT_TRUE(same_bytes(t.free_body, serial.free_body)) << "task " << k;
    ASSERT_TRUE(same_bytes(t.modal_double, serial.modal_double)) << "task " << k;
    ASSERT_TRUE(same_bytes(t.modal_single, serial.modal_single)) << "task " << k;
    ASSERT_TRUE(same_bytes(t.stress, serial.stress)) << "task " << k;
    ASSERT_TRUE(same_bytes(t.max_principal, serial.max_principal)) << "task " << k;
    ASSERT_TRUE(same_bytes(t.direction, serial.direction)) << "task " << k;
    ASSERT_TRUE(same_bytes(t.recovered_max_principal, serial.recovered_max_principal)) << "task " << k;
    ASSERT_TRUE(same_bytes(t.recovered_direction, serial.recovered_direction)) << "task " << k;
  }
  // The results are real: distinct loads gave distinct answers.
  EXPECT_FALSE(same_bytes(threaded[0].supported, threaded[1].supported));
  EXPECT_GT(threaded[1].supported.norm(), 0.0);
}

}  // namespace
}  // namespace fissure
