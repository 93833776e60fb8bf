#include "fissure/base/normal_distribution.hpp"

#include <cmath>
#include <limits>

namespace fissure {

double standard_normal_tail(double z) { return 0.5 * std::erfc(z * 0.70710678118654752440); }

namespace {

// Acklam's approximation of the lower-tail quantile Φ⁻¹(p), p in (0, 1).
double acklam_quantile(double p) {
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01,  -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  constexpr double low = 0.02425;
  if (p < low) {
    const double q = std::sqrt(-2.0 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  if (p > 1.0 - low) {
    const double q = std::sqrt(-2.0 * std::log1p(-p));
    return -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
}

}  // namespace

double standard_normal_tail_quantile(double q) {
  if (!(q > 0.0 && q < 1.0)) {
    if (q == 0.0) return std::numeric_limits<double>::infinity();
    if (q == 1.0) return -std::numeric_limits<double>::infinity();
    return std::numeric_limits<double>::quiet_NaN();
  }
  // Q(z) = q  ⇔  Φ(−z) = q: start from −Φ⁻¹(q), then one Halley step on Q(z) − q, whose
  // derivative is −φ(z), computed from erfc so the upper tail keeps its relative precision.
  double z = -acklam_quantile(q);
  const double e = standard_normal_tail(z) - q;
  const double u = e * 2.50662827463100050242 * std::exp(0.5 * z * z);  // e / φ(z)
  z = z + u / (1.0 - 0.5 * z * u);
  return z;
}

}  // namespace fissure
