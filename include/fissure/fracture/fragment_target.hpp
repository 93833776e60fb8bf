#pragma once
/// The direct control artists ask every peer tool for: "about N fragments". Fissure reaches it by
/// choosing the age. The simulation is causal, so the state at an earlier age is a prefix of the
/// cracks of a later one, and the fragment count never falls as cracks are added: one run to an
/// age with at least N fragments, then a binary search over crack prefixes, gives the age whose
/// fragment count is nearest to N, without re-simulating.
#include "fissure/fracture/simulation.hpp"

namespace fissure {

struct FragmentTargetResult {
  FractureResult result;   ///< the state at `age` (cracks, labels, partial cracks)
  double age = 0.0;        ///< the age chosen: `fissure fracture --age <this>` gives the same state
  bool reached = false;    ///< false when no age reaches N (say why: `reason`)
  std::string reason;
};

/// Simulates from params.age, doubling the age (up to the table's largest age, or until the crack
/// limit) until the fragment count reaches `target`, then returns the prefix nearest to it (ties:
/// the smaller). Without a stress rate the age changes nothing once the load's cracks have opened:
/// `reached` is then false unless the load alone gives the target. Throws as simulate_fracture,
/// and InvalidInput for target < 1.
FragmentTargetResult simulate_to_fragment_count(const FractureBody& body, const FractureParams& params,
                                                const StressField& initial_stress, const Eigen::VectorXd& resistance,
                                                std::uint64_t seed, int target, const SimulationOptions& options = {});

}  // namespace fissure
