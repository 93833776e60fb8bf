#pragma once
/// What a fitted material remembers of its fit (material file version 2, key "fit"): how it was
/// fitted, how well, against which statistics, the posterior its objects draw from, and the rules
/// a later `fissure fracture` needs to reproduce the fitted statistics (the body's resolution, the
/// load and the supports). Written by `fissure fit`; docs/fit.md describes every field.
#include "fissure/exemplar/pattern_stats.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace fissure {

struct MaterialFit {
  std::string method;             ///< "paper" or "smc"
  long long trials = 0;           ///< the budget spent, every seed repeat counted
  std::uint64_t seed = 0;
  double error = 0.0;             ///< mean Eq. 5 of the fitted parameters over fresh seeds
  double error_stddev = 0.0;      ///< its spread over those seeds (sample standard deviation)
  int error_seeds = 0;
  double score = 0.0;             ///< the method's own score of the winner (one trial, or a seed mean)
  PatternStats exemplar;          ///< the exemplar's statistics (exemplar.source: the image)
  double age = 0.0;               ///< the age the fit ran to (also the material's age)

  // The fit body and the rules that reproduce it.
  double body_width = 0.0, body_height = 0.0, body_thickness = 0.0;  ///< m
  int body_tets = 0;              ///< tets the mesher was asked for
  int tets_per_fragment = 0;      ///< the resolution rule: tets = this × exemplar fragments, clamped
  int min_tets = 0, max_tets = 0;
  bool capped = false;            ///< the rule wanted more tets than max_tets
  std::string note;               ///< why, when capped
  double fragment_scale = 0.0;    ///< √(fragment area) on the fit body, m: r_relax's Table 3 reference
  int load_grid = 0;              ///< the load rule: a G × G grid of patch positions…
  double load_inset = 0.0;        ///< …over [inset, 1 − inset] of the top face, drawn uniformly
  /// Pa: the fit body's reference stress for l = 1 (fitted_transfer.hpp), by which another body's
  /// load keeps the fit's stress; 0 in material files written before it (the load is then l·m·g).
  double load_reference_stress = 0.0;
  std::string supports;           ///< "rim-rollers": the default supports

  /// The posterior over the five fitted parameters (Table 3 order, absolute units).
  std::array<double, 5> posterior_mean{}, posterior_stddev{};
  std::vector<std::array<double, 5>> samples;
  std::vector<double> weights;     ///< one per sample, summing to 1
};

struct FractureParams;

/// `params` with its five fitted parameters drawn from the fit's posterior: a sample picked by
/// weight from the stream (seed, "fit-posterior"), so every object fractured with its own seed gets
/// its own parameters ("similar, not identical", paper §6.2). Throws InvalidInput when the fit has
/// no samples or a drawn value is outside the parameter's range.
FractureParams draw_from_posterior(const MaterialFit& fit, const FractureParams& params, std::uint64_t seed);

}  // namespace fissure
