#include "fissure/exemplar/histogram.hpp"

#include "fissure/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fissure {

Histogram Histogram::make(double lo, double hi, int bins) {
  Histogram h;
  h.edges.resize(static_cast<std::size_t>(bins) + 1);
  for (int i = 0; i <= bins; ++i) h.edges[static_cast<std::size_t>(i)] = lo + (hi - lo) * i / bins;
  h.p.assign(static_cast<std::size_t>(bins), 0.0);
  return h;
}

void Histogram::add(double value, double weight) {
  if (p.empty() || !std::isfinite(value)) return;
  const double lo = edges.front(), hi = edges.back();
  const auto bins = static_cast<double>(p.size());
  const double position = (value - lo) / (hi - lo) * bins;
  const auto bin = static_cast<std::size_t>(std::clamp(std::floor(position), 0.0, bins - 1.0));
  p[bin] += weight;
}

double Histogram::total() const { return std::accumulate(p.begin(), p.end(), 0.0); }

void Histogram::normalize() {
  const double sum = total();
  if (sum > 0.0)
    for (double& v : p) v /= sum;
}

bool Histogram::same_bins(const Histogram& other) const {
  if (edges.size() != other.edges.size()) return false;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (std::abs(edges[i] - other.edges[i]) > 1e-12 * (1.0 + std::abs(edges[i]))) return false;
  }
  return true;
}

double earth_movers_distance(const Histogram& a, const Histogram& b, const std::string& what) {
  if (!a.same_bins(b) || a.p.size() != b.p.size() || a.p.empty()) {
    throw InvalidInput(what + ": the two histograms have different bins; compute both with the same settings");
  }
  const double ta = a.total(), tb = b.total();
  // Each histogram as a unit-mass distribution; an empty one as a point mass at the lowest bin.
  double cdf_a = 0.0, cdf_b = 0.0, sum = 0.0;
  for (std::size_t i = 0; i + 1 < a.p.size(); ++i) {
    cdf_a += ta > 0.0 ? a.p[i] / ta : (i == 0 ? 1.0 : 0.0);
    cdf_b += tb > 0.0 ? b.p[i] / tb : (i == 0 ? 1.0 : 0.0);
    sum += std::abs(cdf_a - cdf_b);
  }
  // Δ·Σ|CDF_a − CDF_b| over the range (bins·Δ) = Σ|…| / bins.
  return sum / static_cast<double>(a.p.size());
}

}  // namespace fissure
