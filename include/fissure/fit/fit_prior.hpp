#pragma once
/// The fit's prior (paper Table 3, fracture_params.hpp table3_priors): a uniform box over the five
/// fitted parameters p = (dσ_e, r_relax, v_relax, R_cvar, l), in absolute units once R_cm (the
/// base material's) and √(fragment area) (the exemplar's on the fit body) are known. The fit
/// works in the box's unit cube u ∈ [0, 1]⁵ (u = 0 at the low end), where the prior is uniform
/// and a sequential method's Gaussian steps are isotropic in prior units.
#include "fissure/exemplar/pattern_stats.hpp"
#include "fissure/fracture/fracture_params.hpp"

#include <array>
#include <cstddef>

namespace fissure {

constexpr std::size_t kFitDimensions = 5;
using UnitPoint = std::array<double, kFitDimensions>;

struct PriorBox {
  std::array<std::size_t, kFitDimensions> row{};  ///< fracture_parameter_table() rows, Table 3 order
  std::array<double, kFitDimensions> lo{}, hi{};  ///< absolute bounds
  double fragment_scale = 0.0;                    ///< √(mean fragment area) on the fit body, m

  /// `base` with the five parameters at `u` (each clamped into [0, 1]). A range whose low end
  /// the parameter table excludes (r_relax > 0) starts at 0.1 % of the box above it.
  FractureParams params_at(const FractureParams& base, const UnitPoint& u) const;
  /// The unit-cube coordinates of `params`' five values (not clamped).
  UnitPoint unit_of(const FractureParams& params) const;
};

/// The box for `base` (its R_cm) and a fragment scale (m). Throws InvalidInput for a fragment
/// scale that is not positive and finite.
PriorBox make_prior_box(const FractureParams& base, double fragment_scale);

/// √(mean normalised fragment area × visible area): the exemplar's fragment size carried onto a
/// body whose visible face has `visible_area` m² (paper-gaps §2). Throws InvalidInput when the
/// exemplar has no fragment.
double exemplar_fragment_scale(const PatternStats& exemplar, double visible_area);

}  // namespace fissure
