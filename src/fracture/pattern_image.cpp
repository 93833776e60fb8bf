#include "fissure/fracture/pattern_image.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <algorithm>
#include <cmath>

namespace fissure {

std::vector<std::string> PatternImageOptions::problems() const {
  std::vector<std::string> out;
  if (long_side_px < kMinImageSide || long_side_px > 16384) {
    out.push_back("long_side_px " + std::to_string(long_side_px) + " is outside [" + std::to_string(kMinImageSide) + ", 16384]");
  }
  if (!(line_width_px >= 1.0 && line_width_px <= 64.0)) out.push_back("line_width_px " + format_number(line_width_px) + " is outside [1, 64]");
  return out;
}

void PatternImageOptions::validate() const { throw_if_problems("pattern image options", problems()); }

PatternImage render_pattern_image(const VisiblePattern& pattern, const PatternImageOptions& options) {
  options.validate();
  if (!pattern.has_visible_face) {
    throw InvalidInput(pattern.empty_reason.empty() ? std::string("visible pattern: there is no visible face to draw")
                                                    : pattern.empty_reason);
  }
  const PlanarCrackGraph& g = pattern.graph;
  const Eigen::Vector2d size = g.frame_max - g.frame_min;
  const double scale = options.long_side_px / std::max(size.x(), size.y());  // pixels per metre
  PatternImage image;
  image.metres_per_pixel = 1.0 / scale;
  const int width = std::max(1, static_cast<int>(std::lround(size.x() * scale)));
  const int height = std::max(1, static_cast<int>(std::lround(size.y() * scale)));
  image.drawing.width = width;
  image.drawing.height = height;
  image.drawing.pixels.assign(static_cast<std::size_t>(width) * height, 255);
  auto to_pixels = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d((p.x() - g.frame_min.x()) * scale, (g.frame_max.y() - p.y()) * scale);
  };

  // Cracks: every pixel whose centre is within half the line width of a segment (a capsule).
  const double r = 0.5 * options.line_width_px;
  for (const Crack& crack : g.cracks) {
    for (std::size_t i = 1; i < crack.points.size(); ++i) {
      const Eigen::Vector2d a = to_pixels(crack.points[i - 1]), b = to_pixels(crack.points[i]);
      const Eigen::Vector2d d = b - a;
      const double dd = d.squaredNorm();
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min(a.x(), b.x()) - r - 0.5)));
      const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max(a.x(), b.x()) + r - 0.5)));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min(a.y(), b.y()) - r - 0.5)));
      const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max(a.y(), b.y()) + r - 0.5)));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          const Eigen::Vector2d c(x + 0.5, y + 0.5);
          const double t = dd > 0.0 ? std::clamp((c - a).dot(d) / dd, 0.0, 1.0) : 0.0;
          if ((c - a - t * d).squaredNorm() <= r * r) image.drawing.pixels[static_cast<std::size_t>(y) * width + x] = 0;
        }
      }
    }
  }

  // The region of interest: pixel centres inside a visible triangle (edges included, to 1e-9 of a
  // pixel: round-off of the projection, not geometry).
  std::vector<std::uint8_t> roi(image.drawing.pixels.size(), 0);
  for (const auto& corners : pattern.visible_triangle_corners) {
    const Eigen::Vector2d p0 = to_pixels(corners[0]), p1 = to_pixels(corners[1]), p2 = to_pixels(corners[2]);
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p0.x(), p1.x(), p2.x()}) - 0.5)));
    const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max({p0.x(), p1.x(), p2.x()}) - 0.5)));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p0.y(), p1.y(), p2.y()}) - 0.5)));
    const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max({p0.y(), p1.y(), p2.y()}) - 0.5)));
    auto edge = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
      return ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x()) / std::max((b - a).norm(), 1e-300);
    };
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d c(x + 0.5, y + 0.5);
        const double e0 = edge(p0, p1, c), e1 = edge(p1, p2, c), e2 = edge(p2, p0, c);
        // The y flip makes the triangles clockwise in pixels: inside = all distances ≤ 0.
        if (e0 <= 1e-9 && e1 <= 1e-9 && e2 <= 1e-9) roi[static_cast<std::size_t>(y) * width + x] = 255;
      }
    }
  }
  if (std::find(roi.begin(), roi.end(), 0) != roi.end()) {
    image.roi.width = width;
    image.roi.height = height;
    image.roi.pixels = std::move(roi);
  }
  return image;
}

void write_pattern_image(const std::filesystem::path& path, const PatternImage& image, const std::filesystem::path& roi_path) {
  write_grey_png(path, image.drawing);
  if (!roi_path.empty() && !image.roi.pixels.empty()) write_grey_png(roi_path, image.roi);
}

}  // namespace fissure
