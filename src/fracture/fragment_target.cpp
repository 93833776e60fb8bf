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

// Within ±20 % of the target (at least ±1): what --fragments promises; or within `tolerance`.
bool near_target(int count, int target, double tolerance = 0.2) {
  return std::abs(count - target) <= std::max(tolerance > 0.0 ? 1.0 : 0.0, tolerance * target);
}

// Meshings simulate_to_fragment_mesh_count spends beyond the first.
constexpr int kMaxMeshCountSteps = 8;

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

// The smallest prefix k in [0, n] with count(k) ≥ goal, for a count non-decreasing in k; n when
// none reaches it.
template <class Count>
int smallest_prefix_reaching(int n, int goal, const Count& count) {
  int lo = 0, hi = n;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (count(mid) >= goal) {
      hi = mid;
    } else {
      lo = mid + 1;
    }
  }
  return lo;
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
  const double max_age = fracture_parameter_info("age").max;
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
  int k = smallest_prefix_reaching(n, target, fragments_of);
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
                                                     const SimulationOptions& options, double tolerance) {
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
  // The labeller's count stands in for the meshes' at a ratio measured on the last meshing: the
  // prefix whose labelled count is the target over that ratio is meshed, and the ratio updated
  // (a secant step on the labeller's count, which is cheap). A longer run is simulated when the
  // prefix lies beyond the current one (causal: the shorter run's cracks are its first ones).
  FractureParams p = params;
  p.age = out.age > 0.0 ? out.age : 1.0;
  FractureResult run = out.result;
  const double max_age = fracture_parameter_info("age").max;
  std::map<int, int> labelled;  // crack prefix of `run` → labeller's count
  const auto labelled_of = [&](int k) {
    auto it = labelled.find(k);
    if (it == labelled.end()) it = labelled.emplace(k, label_fragments(body.mesh(), run.cracks, k).count).first;
    return it->second;
  };
  int best_k = static_cast<int>(run.cracks.size()), best = first;
  bool improved = false;  // best_k is a later state than the labeller's, meshed as best_meshes
  std::vector<FragmentMesh> best_meshes;
  std::map<int, int> meshed{{best_k, first}};  // crack prefix → its meshes' count (prefixes of every run alike)
  double ratio = static_cast<double>(first) / std::max(1, labelled_of(best_k));
  for (int step = 0; step < kMaxMeshCountSteps && !near_target(best, target, tolerance); ++step) {
    const int goal = static_cast<int>(std::ceil(target / std::max(ratio, 1e-3)));
    while (labelled_of(static_cast<int>(run.cracks.size())) < goal && p.stress_rate > 0.0 && p.age < max_age &&
           !run.crack_limit_reached) {
      p.age = std::min(2.0 * p.age, max_age);
      run = simulate_fracture(body, p, initial_stress, resistance, seed, options);
      labelled.clear();
    }
    // The smallest prefix labelled ≥ goal, or all.
    int k = smallest_prefix_reaching(static_cast<int>(run.cracks.size()), goal, labelled_of);
    // The meshes' count is nearly monotone in the prefix, but the labeller's ratio to it drifts
    // (fragments under the debris and dust sizes join a neighbour; thin passages it misses): the
    // secant step is kept only inside the bracket the meshings so far give, else the bracket is
    // halved, so a drifting ratio cannot stall the search on a prefix already tried.
    const auto above = std::find_if(meshed.begin(), meshed.end(), [&](const auto& m) { return m.second > target; });
    int lo = 0;
    for (auto it = meshed.begin(); it != above; ++it)
      if (it->second < target) lo = it->first;
    const int hi = above == meshed.end() ? static_cast<int>(run.cracks.size()) + 1 : above->first;
    if (k <= lo || k >= hi || meshed.count(k)) k = (lo + hi) / 2;
    if (k <= lo || k >= hi || meshed.count(k) || k > static_cast<int>(run.cracks.size())) break;  // no new prefix to try
    std::vector<FragmentMesh> meshes = mesh(run, k);
    const int count = static_cast<int>(meshes.size());
    meshed[k] = count;
    ratio = static_cast<double>(count) / std::max(1, labelled_of(k));
    if (std::abs(count - target) < std::abs(best - target)) {
      best = count;
      best_k = k;
      best_meshes = std::move(meshes);
      improved = true;
    }
  }
  if (improved) {
    int k = best_k;
    out.age = cut_to_prefix(body, run, k);
    // A tie of cracks at the prefix's last instant is kept whole, which changes the state.
    out.meshes = k == best_k ? std::move(best_meshes) : mesh(run, k);
    out.result = std::move(run);
  }
  const int count = static_cast<int>(out.meshes.size());
  out.reached = near_target(count, target);
  out.reason = out.reached ? std::string() : shortfall(count, "fragment meshes", target, p.stress_rate);
  return out;
}

}  // namespace fissure
