#include "fissure/fracture/fragment_target.hpp"

#include "fissure/base/error.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace fissure {

namespace {

// Within ±20 % of the target (at least ±1): what --fragments promises.
bool near_target(int count, int target) { return std::abs(count - target) <= std::max(1.0, 0.2 * target); }

// `run` cut to its first k cracks, or to the whole tie of cracks at the k-th crack's time (an
// age cannot split a tie); returns the age of that state.
double cut_to_prefix(const FractureBody& body, FractureResult& run, int& k) {
  const int n = static_cast<int>(run.cracks.size());
  const double age = k == n ? run.simulated_age : (k == 0 ? 0.0 : run.cracks[static_cast<std::size_t>(k - 1)].time);
  if (k < n && k > 0 && run.cracks[static_cast<std::size_t>(k)].time == age) k = run.crack_count_at(age);
  run.crack_limit_reached = run.crack_limit_reached && k == n;
  run.cracks.resize(static_cast<std::size_t>(k));
  run.simulated_age = age;
  run.fragments = label_fragments(body.mesh(), run.cracks, k, &run.partial_cracks);
  return age;
}

// Why the count stayed off the target.
std::string shortfall(int count, const char* what, int target, double stress_rate) {
  return "reached " + std::to_string(count) + " " + what + ", not about " + std::to_string(target) +
         (stress_rate <= 0.0 ? " (with no stress rate the age changes nothing: raise --stress-rate or the load)"
                             : " (the nearest count any age gives)");
}

}  // namespace

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
  out.age = cut_to_prefix(body, run, k);
  out.reached = near_target(run.fragments.count, target);
  if (!out.reached) out.reason = shortfall(run.fragments.count, "fragments", target, p.stress_rate);
  out.result = std::move(run);
  return out;
}

FragmentTargetResult simulate_to_fragment_mesh_count(const FractureBody& body, const FractureParams& params,
                                                     const StressField& initial_stress, const Eigen::VectorXd& resistance,
                                                     std::uint64_t seed, int target, int threads,
                                                     const SimulationOptions& options) {
  FragmentTargetResult out = simulate_to_fragment_count(body, params, initial_stress, resistance, seed, target, options);
  const auto mesh = [&](const FractureResult& r, int k) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<FragmentMesh> meshes = mesh_fragments(body.mesh(), r.cracks, k, threads);
    out.meshing_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++out.meshings;
    return meshes;
  };
  out.meshes = mesh(out.result, static_cast<int>(out.result.cracks.size()));
  const int first = static_cast<int>(out.meshes.size());
  if (near_target(first, target)) {
    out.reached = true;
    out.reason.clear();
    return out;
  }
  // A run that holds the answer: the labeller's own state when its meshes are too many, else
  // a longer one (causal: the labeller's cracks are its first ones), doubling the age.
  FractureParams p = params;
  p.age = out.age > 0.0 ? out.age : 1.0;
  FractureResult run = out.result;
  std::map<int, int> counted;  // crack prefix → meshes
  const auto meshes_of = [&](int k) {
    auto it = counted.find(k);
    if (it == counted.end()) {
      it = counted.emplace(k, static_cast<int>(mesh(run, k).size())).first;
    }
    return it->second;
  };
  int low = 0;  // a prefix with fewer meshes than the target (or 0)
  if (first < target) {
    low = static_cast<int>(run.cracks.size());
    const double max_age = fracture_parameter_table()[static_cast<std::size_t>(find_fracture_parameter("age"))].max;
    for (int doubling = 0; doubling < 20; ++doubling) {
      if (p.stress_rate <= 0.0 || p.age >= max_age || run.crack_limit_reached) break;
      p.age = std::min(2.0 * p.age, max_age);
      run = simulate_fracture(body, p, initial_stress, resistance, seed, options);
      counted.clear();
      if (meshes_of(static_cast<int>(run.cracks.size())) >= target) break;
    }
  }
  const int n = static_cast<int>(run.cracks.size());
  // Smallest prefix in [low, n] with ≥ target meshes (the count is non-decreasing in the prefix
  // but for debris joins, which are rare), then the nearer of it and the one before.
  int lo = low, hi = n;
  if (meshes_of(n) < target) {
    lo = n;
  } else {
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      if (meshes_of(mid) >= target) {
        hi = mid;
      } else {
        lo = mid + 1;
      }
    }
  }
  int k = lo;
  if (k > low && std::abs(meshes_of(k - 1) - target) <= std::abs(meshes_of(k) - target)) --k;
  if (std::abs(meshes_of(k) - target) >= std::abs(first - target)) {  // no better than the labeller's state
    out.reached = false;
    out.reason = shortfall(first, "fragment meshes", target, p.stress_rate);
    return out;
  }
  out.age = cut_to_prefix(body, run, k);
  out.meshes = mesh(run, k);
  out.result = std::move(run);
  const int count = static_cast<int>(out.meshes.size());
  out.reached = near_target(count, target);
  out.reason = out.reached ? std::string() : shortfall(count, "fragment meshes", target, p.stress_rate);
  return out;
}

}  // namespace fissure
