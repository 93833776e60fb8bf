#include "fissure/exemplar/comparison_report.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include "bgr_png.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace fissure {
namespace {

constexpr int kMargin = 20;
constexpr int kLabelHeight = 28;
constexpr int kHistogramHeight = 300;
const cv::Scalar kInk(30, 30, 30);
const cv::Scalar kFaint(200, 200, 200);
const cv::Scalar kLeftColour(190, 140, 80);   // steel blue (BGR): filled bars
const cv::Scalar kRightColour(40, 70, 220);   // red: a step outline over them

void text(cv::Mat& canvas, const std::string& s, cv::Point at, double scale = 0.5, const cv::Scalar& colour = kInk,
          int thickness = 1) {
  cv::putText(canvas, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, thickness, cv::LINE_AA);
}

// The drawing scaled to fit `box` (aspect kept, centred), or a note when there is none.
void draw_image(cv::Mat& canvas, const GreyImage& image, const cv::Rect& box) {
  cv::rectangle(canvas, box, kFaint, 1);
  if (image.width == 0 || image.height == 0) {
    text(canvas, "(statistics only: no drawing)", {box.x + 20, box.y + box.height / 2});
    return;
  }
  const double scale = std::min(static_cast<double>(box.width) / image.width, static_cast<double>(box.height) / image.height);
  const int w = std::max(1, static_cast<int>(std::lround(image.width * scale)));
  const int h = std::max(1, static_cast<int>(std::lround(image.height * scale)));
  const cv::Mat grey(image.height, image.width, CV_8UC1, const_cast<std::uint8_t*>(image.pixels.data()));
  cv::Mat scaled;
  // INTER_AREA averages when shrinking, so 1 px lines of a large tracing stay visible as grey.
  cv::resize(grey, scaled, cv::Size(w, h), 0, 0, scale < 1.0 ? cv::INTER_AREA : cv::INTER_NEAREST);
  cv::Mat colour;
  cv::cvtColor(scaled, colour, cv::COLOR_GRAY2BGR);
  colour.copyTo(canvas(cv::Rect(box.x + (box.width - w) / 2, box.y + (box.height - h) / 2, w, h)));
}

// One histogram panel: the left pattern's bins as bars, the right's as a step line over them.
void draw_histogram(cv::Mat& canvas, const cv::Rect& box, const std::string& title, const Histogram& a, const Histogram& b,
                    const std::string& axis) {
  text(canvas, title, {box.x, box.y - 8}, 0.5, kInk, 1);
  const cv::Rect plot(box.x + 40, box.y + 4, box.width - 50, box.height - 40);
  cv::rectangle(canvas, plot, kFaint, 1);
  const std::size_t bins = a.p.size();
  double top = 0.0;
  for (std::size_t i = 0; i < bins; ++i) top = std::max({top, a.p[i], b.p[i]});
  top = top > 0.0 ? top * 1.1 : 1.0;
  const auto x_of = [&](std::size_t i) { return plot.x + static_cast<int>(std::lround(static_cast<double>(i) * plot.width / bins)); };
  const auto y_of = [&](double p) { return plot.y + plot.height - static_cast<int>(std::lround(p / top * plot.height)); };
  for (std::size_t i = 0; i < bins; ++i) {
    if (a.p[i] <= 0.0) continue;
    cv::rectangle(canvas, cv::Point(x_of(i) + 1, y_of(a.p[i])), cv::Point(x_of(i + 1) - 1, plot.y + plot.height), kLeftColour,
                  cv::FILLED);
  }
  std::vector<cv::Point> step;
  for (std::size_t i = 0; i < bins; ++i) {
    step.emplace_back(x_of(i), y_of(b.p[i]));
    step.emplace_back(x_of(i + 1), y_of(b.p[i]));
  }
  cv::polylines(canvas, step, false, kRightColour, 2, cv::LINE_AA);
  // Axis labels: the range's ends and middle, and the top of the probability scale.
  const double lo = a.edges.front(), hi = a.edges.back();
  text(canvas, format_number(lo, 3), {plot.x - 4, plot.y + plot.height + 16}, 0.4);
  text(canvas, format_number((lo + hi) / 2, 3), {plot.x + plot.width / 2 - 8, plot.y + plot.height + 16}, 0.4);
  text(canvas, format_number(hi, 3), {plot.x + plot.width - 16, plot.y + plot.height + 16}, 0.4);
  text(canvas, axis, {plot.x + plot.width / 2 - 60, plot.y + plot.height + 32}, 0.4);
  text(canvas, format_number(top, 2), {box.x, plot.y + 10}, 0.35);
  text(canvas, "0", {box.x + 24, plot.y + plot.height}, 0.35);
}

std::string counts(const PatternStats& s) {
  return std::to_string(s.fragment_count) + " fragments, " + std::to_string(s.crack_count) + " cracks, " +
         std::to_string(s.junction_count) + " junctions (T/Y/X " + std::to_string(s.t_count) + "/" + std::to_string(s.y_count) +
         "/" + std::to_string(s.x_count) + "), mean junction angle " + format_number(s.mean_junction_angle_deg, 3) + " deg";
}

}  // namespace

void write_comparison_report(const std::filesystem::path& path, const ComparisonReport& r) {
  for (const GreyImage* image : {&r.left_image, &r.right_image}) {
    const auto problems = image->problems();
    if (!problems.empty()) throw InvalidInput(path.string() + ": cannot draw the report: " + problems.front());
  }
  Similarity s;
  try {
    s = pattern_similarity(r.left, r.right, r.weights);
  } catch (const InvalidInput& e) {
    throw InvalidInput(path.string() + ": cannot draw the report: " + e.what());
  }

  const int width = kComparisonReportWidth;
  const int panel = (width - 3 * kMargin) / 2;
  // The drawings' panel height follows the taller aspect, within [panel / 3, panel].
  double aspect = 1.0;  // height / width
  bool any = false;
  for (const GreyImage* image : {&r.left_image, &r.right_image}) {
    if (image->width == 0 || image->height == 0) continue;
    const double a = static_cast<double>(image->height) / image->width;
    aspect = any ? std::max(aspect, a) : a;
    any = true;
  }
  const int image_height = std::clamp(static_cast<int>(std::lround(panel * aspect)), panel / 3, panel);
  const int top = kMargin + 30;
  const int images_y = top + kLabelHeight;
  const int hist_y = images_y + image_height + kMargin + 30;
  const int legend_y = hist_y + kHistogramHeight + 10;
  const int height = legend_y + 90;
  cv::Mat canvas(height, width, CV_8UC3, cv::Scalar(255, 255, 255));

  text(canvas, r.title, {kMargin, kMargin + 14}, 0.65, kInk, 2);
  text(canvas, r.left_label, {kMargin, images_y - 8}, 0.55, kLeftColour, 2);
  text(canvas, r.right_label, {2 * kMargin + panel, images_y - 8}, 0.55, kRightColour, 2);
  draw_image(canvas, r.left_image, {kMargin, images_y, panel, image_height});
  draw_image(canvas, r.right_image, {2 * kMargin + panel, images_y, panel, image_height});

  const int hist_w = (width - 4 * kMargin) / 3;
  const auto term = [](const char* name, double weight, double emd) {
    return std::string(name) + ": EMD " + format_number(emd, 3) + " x " + format_number(weight, 3);
  };
  draw_histogram(canvas, {kMargin, hist_y, hist_w, kHistogramHeight}, term("fragment areas", r.weights.fragment, s.fragment),
                 r.left.fragment_area_hist, r.right.fragment_area_hist, "log10 area / total area");
  draw_histogram(canvas, {2 * kMargin + hist_w, hist_y, hist_w, kHistogramHeight},
                 term("crack lengths", r.weights.crack, s.crack), r.left.crack_length_hist, r.right.crack_length_hist,
                 "log10 length / sqrt(total area)");
  draw_histogram(canvas, {3 * kMargin + 2 * hist_w, hist_y, hist_w, kHistogramHeight},
                 term("junction density", r.weights.junction, s.junction), r.left.junction_density_hist,
                 r.right.junction_density_hist, "log10(1 + junctions per window)");

  cv::rectangle(canvas, cv::Rect(kMargin, legend_y + 4, 30, 12), kLeftColour, cv::FILLED);
  text(canvas, r.left_label + ": " + counts(r.left), {kMargin + 40, legend_y + 15}, 0.45);
  cv::line(canvas, {kMargin, legend_y + 36}, {kMargin + 30, legend_y + 36}, kRightColour, 2, cv::LINE_AA);
  text(canvas, r.right_label + ": " + counts(r.right), {kMargin + 40, legend_y + 40}, 0.45);
  text(canvas,
       "Eq. 5 error " + format_number(s.total, 4) + " = " + format_number(r.weights.fragment, 3) + " x " +
           format_number(s.fragment, 3) + " + " + format_number(r.weights.crack, 3) + " x " + format_number(s.crack, 3) +
           " + " + format_number(r.weights.junction, 3) + " x " + format_number(s.junction, 3),
       {kMargin, legend_y + 72}, 0.6, kInk, 2);
  detail::write_bgr_png(path, canvas);
}

}  // namespace fissure
