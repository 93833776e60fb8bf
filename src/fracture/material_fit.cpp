#include "fissure/fracture/material_fit.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/fracture/fracture_params.hpp"

namespace fissure {

FractureParams draw_from_posterior(const MaterialFit& fit, const FractureParams& params, std::uint64_t seed) {
  if (fit.samples.empty() || fit.samples.size() != fit.weights.size()) {
    throw InvalidInput("the material's fit has no posterior samples to draw from");
  }
  double total = 0.0;
  for (double w : fit.weights) total += w;
  Rng rng = Rng::derive(seed, "fit-posterior");
  const double pick = rng.uniform() * total;
  std::size_t chosen = fit.samples.size() - 1;
  double c = 0.0;
  for (std::size_t i = 0; i < fit.weights.size(); ++i) {
    c += fit.weights[i];
    if (pick < c) {
      chosen = i;
      break;
    }
  }
  FractureParams p = params;
  for (std::size_t k = 0; k < fit.samples[chosen].size(); ++k) {
    const int row = find_fracture_parameter(table3_priors()[k].name);
    parameter_value(p, static_cast<std::size_t>(row)) = fit.samples[chosen][k];
  }
  p.validate();
  return p;
}

}  // namespace fissure
