#pragma once
/// The direct control artists ask every peer tool for: "about N fragments". Fissure reaches it by
/// choosing the age. The simulation is causal, so the state at an earlier age is a prefix of the
/// cracks of a later one, and the fragment count never falls as cracks are added: one run to an
/// age with at least N fragments, then a binary search over crack prefixes, gives the age whose
/// fragment count is nearest to N, without re-simulating.
#include "fissure/fracture/fragment_mesh.hpp"
#include "fissure/fracture/simulation.hpp"

#include <vector>

namespace fissure {

struct FragmentTargetResult {
  FractureResult result;   ///< the state at `age` (cracks, labels, partial cracks)
  double age = 0.0;        ///< the age chosen: `fissure fracture --age <this>` gives the same state
  bool reached = false;    ///< false when no age reaches N (say why: `reason`)
  std::string reason;
  /// simulate_to_fragment_mesh_count only: the closed meshes of `result` (their count is the
  /// one aimed at).
  std::vector<FragmentMesh> meshes;
  int meshings = 0;             ///< how many times it meshed the fragments to count them
  double meshing_seconds = 0.0;  ///< the time those meshings took
};

/// Simulates from params.age, doubling the age (up to the table's largest age, or until the crack
/// limit) until the fragment count reaches `target`, then returns the prefix nearest to it (ties:
/// the smaller). Without a stress rate the age changes nothing once the load's cracks have opened:
/// `reached` is then false unless the load alone gives the target. Throws as simulate_fracture,
/// and InvalidInput for target < 1.
FragmentTargetResult simulate_to_fragment_count(const FractureBody& body, const FractureParams& params,
                                                const StressField& initial_stress, const Eigen::VectorXd& resistance,
                                                std::uint64_t seed, int target, const SimulationOptions& options = {});

/// The same, aimed at the closed meshes' count (mesh_fragments on `threads` threads), which is
/// the one an artist sees. The labeller's count runs ahead of it on dense patterns (it probes a
/// few points per tet face and misses thin passages beyond a crack's tip: 763 labelled against
/// 479 meshes at 22K tets and N = 1000). From the labeller's state, when its meshes are off by
/// more than `tolerance` (relative; at least ±1 when positive), the labeller's count stands in
/// for the meshes' at the ratio of the last meshing: the prefix labelled N / ratio is meshed
/// (the age doubled when the run is too short) and the ratio updated, up to 8 times; a step that
/// falls outside the bracket of prefixes meshed below and above N (or on one already meshed)
/// halves the bracket instead. The nearest state met is kept. Costs one meshing when the
/// labeller is close, else up to 9. `meshes` holds the result's meshes. Throws as
/// simulate_to_fragment_count. It aims within `tolerance` (10 %) and reports `reached` within
/// the ±20 % it promises: stopping at the first state within 20 % left a 0.4 m tile's counts
/// (3,000 tets) at its lower edge (64–66 meshes for 80 asked, seeds 1–6); aiming at 10 % gives 74–80 for
/// one meshing more.
FragmentTargetResult simulate_to_fragment_mesh_count(const FractureBody& body, const FractureParams& params,
                                                     const StressField& initial_stress, const Eigen::VectorXd& resistance,
                                                     std::uint64_t seed, int target, int threads,
                                                     const SimulationOptions& options = {}, double tolerance = 0.1);

}  // namespace fissure
