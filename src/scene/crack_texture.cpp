#include "fissure/scene/crack_texture.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"
#include "fissure/mesh/appearance_transfer.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <set>
#include <utility>

namespace fissure {
namespace {

using Point = std::array<double, 3>;
using EdgeKey = std::pair<Point, Point>;  // the ends by position, ordered: the two triangles along
                                          // an edge may hold their own copies of its vertices

Point point_of(const Eigen::MatrixX3d& vertices, int v) { return {vertices(v, 0), vertices(v, 1), vertices(v, 2)}; }

EdgeKey edge_key(const Eigen::MatrixX3d& vertices, int a, int b) {
  Point p = point_of(vertices, a), q = point_of(vertices, b);
  if (q < p) std::swap(p, q);
  return {p, q};
}

// Draws segment p–q (pixels) into `image` with an antialiased width `width`: each pixel takes
// the coverage 1 − (distance − width/2) clamped to [0, 1], kept as the maximum over segments.
void draw_segment(GreyImage& image, Eigen::Vector2d p, Eigen::Vector2d q, double width) {
  const double reach = 0.5 * width + 1.0;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min(p.x(), q.x()) - reach)));
  const int x1 = std::min(image.width - 1, static_cast<int>(std::ceil(std::max(p.x(), q.x()) + reach)));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min(p.y(), q.y()) - reach)));
  const int y1 = std::min(image.height - 1, static_cast<int>(std::ceil(std::max(p.y(), q.y()) + reach)));
  const Eigen::Vector2d d = q - p;
  const double length2 = d.squaredNorm();
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Eigen::Vector2d c(x + 0.5, y + 0.5);  // the pixel's centre
      const double s = length2 > 0.0 ? std::clamp((c - p).dot(d) / length2, 0.0, 1.0) : 0.0;
      const double distance = (c - (p + s * d)).norm();
      const double coverage = std::clamp(0.5 * width + 0.5 - distance, 0.0, 1.0);
      auto& pixel = image.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x)];
      pixel = std::max(pixel, static_cast<std::uint8_t>(std::lround(255.0 * coverage)));
    }
  }
}

}  // namespace

GreyImage crack_texture(const std::vector<FragmentMesh>& fragments, const SurfaceAppearance& appearance,
                        const CrackTextureOptions& options) {
  if (!(options.size >= 16 && options.size <= 16384)) {
    throw InvalidInput("crack texture size " + std::to_string(options.size) + " is outside [16, 16384] pixels");
  }
  if (!(options.line_width_px > 0.0 && options.line_width_px <= 64.0)) {
    throw InvalidInput("crack texture line width " + format_number(options.line_width_px) + " is outside (0, 64] pixels");
  }
  GreyImage image;
  if (!appearance.has_uvs() || appearance.empty()) return image;
  image.width = image.height = options.size;
  image.pixels.assign(static_cast<std::size_t>(options.size) * static_cast<std::size_t>(options.size), 0);
  const AppearanceTransfer transfer(appearance);
  const double side = options.size;
  for (const FragmentMesh& f : fragments) {
    // Which edges have a crack face on them.
    std::set<EdgeKey> on_crack;
    for (Eigen::Index t = 0; t < f.triangles.rows(); ++t) {
      if (f.triangle_crack[static_cast<std::size_t>(t)] < 0) continue;
      for (int k = 0; k < 3; ++k) on_crack.insert(edge_key(f.vertices, f.triangles(t, k), f.triangles(t, (k + 1) % 3)));
    }
    if (on_crack.empty()) continue;  // a fragment no crack bounds
    for (Eigen::Index t = 0; t < f.triangles.rows(); ++t) {
      if (f.triangle_crack[static_cast<std::size_t>(t)] >= 0) continue;
      // The outer triangle's UVs as the exported fragment has them: from the input triangle
      // nearest its centroid.
      const Eigen::Vector3d centroid = (f.vertices.row(f.triangles(t, 0)) + f.vertices.row(f.triangles(t, 1)) +
                                        f.vertices.row(f.triangles(t, 2))).transpose() / 3.0;
      int source = -1;
      for (int k = 0; k < 3; ++k) {
        const int a = f.triangles(t, k), b = f.triangles(t, (k + 1) % 3);
        if (!on_crack.count(edge_key(f.vertices, a, b))) continue;
        if (source < 0) source = transfer.nearest_triangle(centroid);
        const Eigen::Vector2d ua = transfer.uv_at(source, f.vertices.row(a).transpose());
        const Eigen::Vector2d ub = transfer.uv_at(source, f.vertices.row(b).transpose());
        if (!ua.allFinite() || !ub.allFinite()) continue;
        // The unit tile of the edge's midpoint.
        const Eigen::Vector2d tile = (0.5 * (ua + ub)).array().floor();
        const auto pixel = [&](const Eigen::Vector2d& uv) {
          const Eigen::Vector2d local = uv - tile;
          return Eigen::Vector2d(local.x() * side, (1.0 - local.y()) * side);
        };
        draw_segment(image, pixel(ua), pixel(ub), options.line_width_px);
      }
    }
  }
  return image;
}

std::string crack_texture_file_name(const std::string& body_path) {
  std::string name = body_path.starts_with('/') ? body_path.substr(1) : body_path;
  for (char& c : name) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_';
    if (!keep) c = '_';
  }
  return (name.empty() ? std::string("body") : name) + ".png";
}

}  // namespace fissure
