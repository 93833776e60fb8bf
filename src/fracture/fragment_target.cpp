#include "fissure/fracture/fragment_target.hpp"

#include "fissure/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace fissure {

FragmentTargetResult simulate_to_fragment_count(const FractureBody& body, const FractureParams& params,
                                                const StressField& initial_stress, const Eigen::VectorXd& resistance,
                                                std::uint64_t seed, int target, const SimulationOptions& options) {
  if (target < 1) throw InvalidInput("--fragments " + std::to_string(target) + " must be at least 1");
  FractureParams p = params;
  if (!(p.age > 0.0)) p.age = 1.0;
  FractureResult run = simulate_fracture(body, p, initial_stress, resistance, seed, options);
  const double max_age = fracture_parameter_table()[static_cast<std::size_t>(find_fracture_parameter("age"))].max;
  for (int doubling = 0; doubling < 20 && run.fragments.count < target && !run.crack_limit_reached; ++doubling) {
    if (p.stress_rate <= 0.0 || p.age >= max_age) break;  // a longer age opens nothing more, or is out of range
    p.age = std::min(2.0 * p.age, max_age);
    run = simulate_fracture(body, p, initial_stress, resistance, seed, options);
  }
  FragmentTargetResult out;
  const int n = static_cast<int>(run.cracks.size());
  // Fragment counts of crack prefixes, each labelled once.
  std::vector<int> counted(static_cast<std::size_t>(n) + 1, -1);
  auto fragments_of = [&](int k) {
    int& c = counted[static_cast<std::size_t>(k)];
    if (c < 0) c = label_fragments(body.mesh(), run.cracks, k).count;
    return c;
  };
  // Smallest prefix with ≥ target fragments (the count is non-decreasing in the prefix).
  int lo = 0, hi = n;
  if (fragments_of(n) < target) {
    lo = n;
  } else {
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      if (fragments_of(mid) >= target) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
  }
  int k = lo;
  if (k > 0 && std::abs(fragments_of(k - 1) - target) <= std::abs(fragments_of(k) - target)) --k;
  // The age of the state with k cracks: the k-th crack's time (crack_count_at counts cracks at
  // or before an age), or 0 for none; the full run's age when all cracks are kept.
  out.age = k == n ? run.simulated_age : (k == 0 ? 0.0 : run.cracks[static_cast<std::size_t>(k - 1)].time);
  if (k < n && k > 0 && run.cracks[static_cast<std::size_t>(k)].time == out.age) {
    // Cracks tied at one instant cannot be split by an age: keep the whole tie.
    k = run.crack_count_at(out.age);
  }
  run.cracks.resize(static_cast<std::size_t>(k));
  run.simulated_age = out.age;
  run.crack_limit_reached = run.crack_limit_reached && k == n;
  run.fragments = label_fragments(body.mesh(), run.cracks, k, &run.partial_cracks);
  out.reached = std::abs(run.fragments.count - target) <= std::max(1.0, 0.2 * target);
  if (!out.reached) {
    out.reason = "reached " + std::to_string(run.fragments.count) + " fragments, not about " + std::to_string(target) +
                 (p.stress_rate <= 0.0 ? " (with no stress rate the age changes nothing: raise --stress-rate or the load)"
                                       : " (the nearest count any age gives)");
  }
  out.result = std::move(run);
  return out;
}

}  // namespace fissure
