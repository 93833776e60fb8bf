#pragma once
/// Fixed-bin histograms and the exact 1-D Earth Mover's Distance between them (paper Eq. 5).

#include <string>
#include <vector>

namespace fissure {

/// Equal-width bins over [edges.front(), edges.back()]; p sums to 1 (all zero when nothing was
/// counted). Values outside the range are clamped into the first or last bin, so no sample is
/// lost (a fragment larger than the top bin still counts).
struct Histogram {
  std::vector<double> edges;
  std::vector<double> p;

  /// `bins` equal bins over [lo, hi].
  static Histogram make(double lo, double hi, int bins);
  void add(double value, double weight = 1.0);
  /// Scales p to unit mass (no-op when empty).
  void normalize();
  double total() const;
  bool same_bins(const Histogram& other) const;
};

/// Exact 1-D EMD between two unit-mass histograms on the same bins: the L1 distance between
/// their cumulative distributions times the bin width (Rubner et al. 1998 for 1-D), divided by
/// the bins' range so the result is dimensionless in [0, 1): 0 for identical histograms,
/// (bins − 1)/bins when all mass moves from the first bin to the last (centre to centre). An empty histogram is compared as a point mass
/// at the lowest bin. Throws InvalidInput when the bins differ (naming `what`).
double earth_movers_distance(const Histogram& a, const Histogram& b, const std::string& what = "histogram");

}  // namespace fissure
