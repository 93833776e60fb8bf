#pragma once
// Synthetic crack drawings with known answers, made by the tests (OpenCV drawing on a canvas).

#include "fissure/exemplar/crack_image.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numbers>

namespace fissure::test {

/// White lines on black (8-bit, 1 channel).
inline cv::Mat blank_canvas(int width, int height) { return cv::Mat(height, width, CV_8U, cv::Scalar(0)); }

/// Lines at every `pitch` px across the whole canvas, starting at pitch/2: an n × n grid of
/// square cells (n = size / pitch), the outer ring cut by the frame.
inline cv::Mat grid_drawing(int size, int pitch, int line_width, bool antialiased = false) {
  cv::Mat c = blank_canvas(size, size);
  const int type = antialiased ? cv::LINE_AA : cv::LINE_8;
  for (int p = pitch / 2; p < size; p += pitch) {
    cv::line(c, {p, 0}, {p, size - 1}, cv::Scalar(255), line_width, type);
    cv::line(c, {0, p}, {size - 1, p}, cv::Scalar(255), line_width, type);
  }
  return c;
}

/// A dense network of oblique crossings: vertical lines every `pitch` px from pitch/2, and lines
/// of slope 1/2 whose intercepts step by `pitch` from −size/2. Thick strokes crossing at 63° thin
/// to pairs of close junctions: the stress case of junction contraction.
inline cv::Mat oblique_grid_drawing(int size, int pitch, int line_width) {
  cv::Mat c = blank_canvas(size, size);
  for (int x = pitch / 2; x < size; x += pitch) cv::line(c, {x, 0}, {x, size - 1}, cv::Scalar(255), line_width);
  for (int b = -size / 2; b < size; b += pitch) cv::line(c, {0, b}, {size - 1, b + size / 2}, cv::Scalar(255), line_width);
  return c;
}

/// A closed grid of `cells` × `cells` squares of `pitch` px, drawn inside a margin (its outer
/// frame included), centred on a canvas of `size`: every cell is enclosed, the outside is one
/// region touching the border.
inline cv::Mat closed_grid_drawing(int size, int cells, int pitch, int line_width) {
  cv::Mat c = blank_canvas(size, size);
  const int extent = cells * pitch, origin = (size - extent) / 2;
  for (int i = 0; i <= cells; ++i) {
    const int p = origin + i * pitch;
    cv::line(c, {p, origin}, {p, origin + extent}, cv::Scalar(255), line_width, cv::LINE_8);
    cv::line(c, {origin, p}, {origin + extent, p}, cv::Scalar(255), line_width, cv::LINE_8);
  }
  return c;
}

/// Brick wall: horizontal lines every `pitch`, vertical joints offset by half a brick on
/// alternate rows: every interior junction is a T at 90°.
inline cv::Mat brick_drawing(int size, int pitch, int line_width) {
  cv::Mat c = blank_canvas(size, size);
  for (int row = 0; row * pitch + pitch / 2 < size; ++row) {
    const int y = row * pitch + pitch / 2;
    cv::line(c, {0, y}, {size - 1, y}, cv::Scalar(255), line_width, cv::LINE_8);
    const int next = y + pitch;
    const int shift = (row % 2) ? pitch : 0;
    for (int x = shift - 2 * pitch + pitch / 2; x < size; x += 2 * pitch) {
      if (x < 0) continue;
      cv::line(c, {x, y}, {x, std::min(next, size - 1)}, cv::Scalar(255), line_width, cv::LINE_8);
    }
  }
  return c;
}

/// Regular hexagons (pointy top) of circumradius `r`: every interior junction is a Y at 120°.
inline cv::Mat honeycomb_drawing(int size, double r, int line_width) {
  cv::Mat c = blank_canvas(size, size);
  const double dx = std::sqrt(3.0) * r, dy = 1.5 * r;
  for (int row = -1; row * dy < size + r; ++row) {
    for (int col = -1; col * dx < size + dx; ++col) {
      const double cx = col * dx + (row % 2 ? dx / 2 : 0.0), cy = row * dy;
      std::vector<cv::Point> hex;
      for (int k = 0; k < 6; ++k) {
        const double a = std::numbers::pi / 180.0 * (60.0 * k - 30.0);
        hex.emplace_back(static_cast<int>(std::lround(cx + r * std::cos(a))), static_cast<int>(std::lround(cy + r * std::sin(a))));
      }
      cv::polylines(c, hex, true, cv::Scalar(255), line_width, cv::LINE_8);
    }
  }
  return c;
}

inline GreyImage to_grey_image(const cv::Mat& m) {
  GreyImage g;
  g.width = m.cols;
  g.height = m.rows;
  g.pixels.assign(m.datastart, m.dataend);
  return g;
}

}  // namespace fissure::test
