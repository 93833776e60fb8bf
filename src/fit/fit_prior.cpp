#include "fissure/fit/fit_prior.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace fissure {

PriorBox make_prior_box(const FractureParams& base, double fragment_scale) {
  if (!(fragment_scale > 0.0) || !std::isfinite(fragment_scale)) {
    throw InvalidInput("fit prior: the fragment scale " + format_number(fragment_scale) + " m is not positive");
  }
  PriorBox box;
  box.fragment_scale = fragment_scale;
  for (std::size_t k = 0; k < kFitDimensions; ++k) {
    const FitPrior& prior = table3_priors()[k];
    const int row = find_fracture_parameter(prior.name);
    if (row < 0) throw InvalidInput(std::string("table3_priors names ") + prior.name + ", not a parameter");
    box.row[k] = static_cast<std::size_t>(row);
    double reference = 1.0;
    switch (prior.reference) {
      case PriorReference::ResistanceMean: reference = base.resistance_mean; break;
      case PriorReference::FragmentScale: reference = fragment_scale; break;
      case PriorReference::None: break;
    }
    box.lo[k] = prior.min_fraction * reference;
    box.hi[k] = prior.max_fraction * reference;
  }
  return box;
}

FractureParams PriorBox::params_at(const FractureParams& base, const UnitPoint& u) const {
  const auto& table = fracture_parameter_table();
  FractureParams p = base;
  for (std::size_t k = 0; k < kFitDimensions; ++k) {
    double t = std::clamp(u[k], 0.0, 1.0);
    const ParameterInfo& info = table[row[k]];
    // r_relax = 0 is outside its range (and means "no relaxation", which 0.1 % of the box is
    // already, far below an element).
    if (info.min_exclusive && lo[k] <= info.min) t = std::max(t, 1e-3);
    parameter_value(p, row[k]) = lo[k] + t * (hi[k] - lo[k]);
  }
  return p;
}

UnitPoint PriorBox::unit_of(const FractureParams& params) const {
  UnitPoint u{};
  for (std::size_t k = 0; k < kFitDimensions; ++k) {
    u[k] = hi[k] > lo[k] ? (parameter_value(params, row[k]) - lo[k]) / (hi[k] - lo[k]) : 0.0;
  }
  return u;
}

double exemplar_fragment_scale(const PatternStats& exemplar, double visible_area) {
  if (exemplar.fragment_areas.empty()) {
    throw InvalidInput(exemplar.source + ": the exemplar has no fragment, so there is nothing to fit");
  }
  const double mean = std::accumulate(exemplar.fragment_areas.begin(), exemplar.fragment_areas.end(), 0.0) /
                      static_cast<double>(exemplar.fragment_areas.size());
  return std::sqrt(mean * visible_area);
}

}  // namespace fissure
