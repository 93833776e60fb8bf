#include "fissure/fit/voronoi_baseline.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/base/rng.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace fissure {

GreyImage draw_voronoi_baseline(double width, double height, int cells, std::uint64_t seed, const PatternImageOptions& options) {
  if (!(std::isfinite(width) && std::isfinite(height) && width > 0.0 && height > 0.0)) {
    throw InvalidInput("Voronoi baseline: the face " + format_number(width) + " x " + format_number(height) + " m is not positive");
  }
  if (cells < 1 || cells > 1'000'000) throw InvalidInput("Voronoi baseline: " + std::to_string(cells) + " cells are outside [1, 1000000]");
  options.validate();
  const double m = std::max(width, height) / options.long_side_px;  // metres per pixel
  GreyImage image;
  image.width = std::max(1, static_cast<int>(std::lround(width / m)));
  image.height = std::max(1, static_cast<int>(std::lround(height / m)));
  image.pixels.assign(static_cast<std::size_t>(image.width) * image.height, 255);

  Rng rng = Rng::derive(seed, "voronoi-baseline");
  std::vector<Eigen::Vector2d> points(static_cast<std::size_t>(cells));
  for (Eigen::Vector2d& p : points) {
    const double x = rng.uniform(0.0, width);
    p = {x, rng.uniform(0.0, height)};
  }
  // Points sorted by x: a candidate whose x gap alone puts it beyond reach is skipped.
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const double half = 0.5 * options.line_width_px * m;
  for (int j = 0; j < image.height; ++j) {
    for (int i = 0; i < image.width; ++i) {
      const Eigen::Vector2d p((i + 0.5) * m, height - (j + 0.5) * m);  // rows run against y, as in render_pattern_image
      std::size_t nearest = 0;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < points.size(); ++k) {
        const double d = (points[k] - p).squaredNorm();
        if (d < best) best = d, nearest = k;
      }
      // The distance to the cell's boundary is the least distance to a bisector with another
      // point, (|p − q|² − |p − s|²) / (2|q − s|) ≥ (|p − q| − |p − s|) / 2: only points within
      // |p − s| + 2·half of p can bring it under `half`.
      const double reach = std::sqrt(best) + 2.0 * half;
      double boundary = std::numeric_limits<double>::infinity();
      const auto lo = std::lower_bound(points.begin(), points.end(), p.x() - reach,
                                       [](const Eigen::Vector2d& q, double x) { return q.x() < x; });
      for (auto it = lo; it != points.end() && it->x() <= p.x() + reach; ++it) {
        const std::size_t k = static_cast<std::size_t>(it - points.begin());
        if (k == nearest) continue;
        const double gap = (points[k] - points[nearest]).norm();
        if (gap == 0.0) continue;  // a repeated point adds no boundary
        boundary = std::min(boundary, ((points[k] - p).squaredNorm() - best) / (2.0 * gap));
      }
      if (boundary <= half) image.pixels[static_cast<std::size_t>(j) * image.width + i] = 0;
    }
  }
  return image;
}

}  // namespace fissure
