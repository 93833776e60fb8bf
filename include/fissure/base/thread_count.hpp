#pragma once
/// Fissure's one thread-count setting. Fissure's own parallel loops take it as their default, and
/// the libraries Fissure calls are held to it where they are wrapped (CHOLMOD's OpenMP team and
/// OpenBLAS in fem/sparse_cholesky.cpp). Results never depend on it (parallel.hpp).

namespace fissure {

/// Sets the thread count for all later work. Throws InvalidInput unless 1 ≤ n ≤ 1024. Set it
/// before work starts: a library's worker pool that is already busy keeps its size until then.
void set_thread_count(int n);

/// The current thread count: set_thread_count's value; else the FISSURE_THREADS environment
/// variable when it holds an integer in [1, 1024]; else hardware_threads().
int thread_count();

}  // namespace fissure
