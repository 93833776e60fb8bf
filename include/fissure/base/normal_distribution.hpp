#pragma once
/// The standard normal distribution's tail and quantile, to full double precision: for mapping
/// a Gaussian random field onto another distribution by its quantiles (resistance_field.hpp).

namespace fissure {

/// Q(z) = P(Z > z) = erfc(z/√2)/2 for a standard normal Z; accurate in both tails (no 1 − Φ).
double standard_normal_tail(double z);

/// The z with standard_normal_tail(z) = q, for q in (0, 1): Acklam's rational approximation
/// (relative error 1.2e-9) refined by one Halley step on erfc, which leaves a few ulps. q at or
/// outside (0, 1) gives ∓infinity or NaN.
double standard_normal_tail_quantile(double q);

}  // namespace fissure
