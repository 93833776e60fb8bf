#pragma once
/// Loads past all reason. A load in newtons typed with a few digits too many (1e300 N) is not an
/// error the solver sees: the stress is finite, every element is over its resistance at age 0,
/// and the body shatters into one piece per crack the mesh allows. The run is valid physics, so
/// it is not refused; it is said, so the user can tell a typo from a hammer blow.
#include "fissure/fem/stress.hpp"
#include "fissure/fracture/fracture_params.hpp"

#include <optional>
#include <string>

namespace fissure {

/// When more than half the tets (by count) start with their max principal stress at or above
/// the material's mean resistance R_cm, the sentence saying so ("the loads stress 97 % of the
/// tets past the material's mean resistance (2.5e6 Pa) at age 0, the largest to 3e295 Pa: it
/// shatters at once; are the forces in newtons?"); otherwise nothing. A real impact over-stresses
/// the region around its patch, not most of the body.
std::optional<std::string> overload_note(const StressField& initial, const FractureParams& params);

}  // namespace fissure
