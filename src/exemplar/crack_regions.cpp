// Steps 1 and 6 of extract_crack_graph: the pixel regions (crack_graph_steps.hpp).

#include "crack_graph_steps.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>

namespace fissure::detail {

CrackRegions label_regions(const CrackMask& mask, double min_fragment_area, CrackGraphDiagnostics& diag) {
  const int w = mask.width, h = mask.height;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  CrackRegions r;
  // Cracks outside the region of interest do not count.
  r.crack.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    r.crack[i] = mask.crack[i] && mask.inside(static_cast<std::int64_t>(i));
  }
  {
    cv::Mat background(h, w, CV_8U);
    for (int y = 0; y < h; ++y) {
      std::uint8_t* row = background.ptr<std::uint8_t>(y);
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        row[x] = mask.inside(static_cast<std::int64_t>(i)) && !r.crack[i] ? 255 : 0;
      }
    }
    r.label_storage.resize(n);
    r.labels = cv::Mat(h, w, CV_32S, r.label_storage.data());
    r.region_count = cv::connectedComponentsWithStats(background, r.labels, r.stats, r.centroids, 4, CV_32S);
  }
  r.small.assign(static_cast<std::size_t>(r.region_count), 0);
  for (int label = 1; label < r.region_count; ++label) {
    r.small[static_cast<std::size_t>(label)] = r.stats.at<int>(label, cv::CC_STAT_AREA) < min_fragment_area;
    diag.small_fragments_dropped += r.small[static_cast<std::size_t>(label)];
  }
  for (int y = 0; y < h; ++y) {
    int* row = r.labels.ptr<int>(y);
    for (int x = 0; x < w; ++x) {
      if (row[x] > 0 && r.small[static_cast<std::size_t>(row[x])]) {
        r.crack[static_cast<std::size_t>(y) * w + x] = 1;
        row[x] = 0;
      }
    }
  }
  for (std::uint8_t c : r.crack) diag.crack_pixels += c;
  return r;
}

std::vector<Fragment> collect_fragments(const CrackMask& mask, CrackRegions& regions, double min_area,
                                        bool assign_crack_pixels, std::vector<std::int32_t>& fragment_of,
                                        CrackGraphDiagnostics& diag) {
  const int w = mask.width, h = mask.height;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  const std::vector<std::uint8_t>& crack = regions.crack;
  const cv::Mat& stats = regions.stats;
  std::vector<Fragment> fragments;
  fragment_of.assign(static_cast<std::size_t>(regions.region_count), -1);
  for (int label = 1; label < regions.region_count; ++label) {
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    if (regions.small[static_cast<std::size_t>(label)]) continue;
    if (area < min_area) {
      ++diag.small_fragments_dropped;
      continue;
    }
    Fragment f;
    f.area = area;
    f.centroid = Eigen::Vector2d(regions.centroids.at<double>(label, 0), regions.centroids.at<double>(label, 1));
    const int left = stats.at<int>(label, cv::CC_STAT_LEFT), top = stats.at<int>(label, cv::CC_STAT_TOP);
    const int right = left + stats.at<int>(label, cv::CC_STAT_WIDTH) - 1;
    const int bottom = top + stats.at<int>(label, cv::CC_STAT_HEIGHT) - 1;
    f.touches_border = left == 0 || top == 0 || right == w - 1 || bottom == h - 1;
    fragment_of[static_cast<std::size_t>(label)] = static_cast<std::int32_t>(fragments.size());
    fragments.push_back(f);
  }
  int* label = regions.labels.ptr<int>(0);
  auto fragment_at = [&](std::size_t i) { return fragment_of[static_cast<std::size_t>(label[i])]; };
  if (!mask.roi.empty()) {
    // A fragment next to a pixel outside the ROI is cut by the ROI edge.
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int id = fragment_at(static_cast<std::size_t>(y) * w + x);
        if (id < 0 || fragments[static_cast<std::size_t>(id)].touches_border) continue;
        for (int k = 0; k < 8; k += 2) {
          const int qx = x + kDx[k], qy = y + kDy[k];
          if (qx >= 0 && qy >= 0 && qx < w && qy < h && !mask.inside(static_cast<std::int64_t>(qy) * w + qx)) {
            fragments[static_cast<std::size_t>(id)].touches_border = true;
          }
        }
      }
  }
  if (assign_crack_pixels && !fragments.empty()) {
    // Crack pixels go to the nearest fragment, found by a breadth-first flood from the
    // fragments' edges across the strokes (4-neighbour steps, neighbours in a fixed order, so
    // ties resolve the same way every time). Memory: one queue of crack pixels, no distance map.
    std::vector<std::size_t> queue;
    auto claim = [&](std::size_t i, int from) {
      label[i] = from;
      fragments[static_cast<std::size_t>(fragment_of[static_cast<std::size_t>(from)])].area += 1.0;
      queue.push_back(i);
    };
    const int step[4] = {-w, 1, w, -1};
    auto neighbours_ok = [&](std::size_t i, int k) {
      const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
      return (k == 0 && y > 0) || (k == 1 && x < w - 1) || (k == 2 && y < h - 1) || (k == 3 && x > 0);
    };
    for (std::size_t i = 0; i < n; ++i) {
      if (!crack[i] || !mask.inside(static_cast<std::int64_t>(i))) continue;
      for (int k = 0; k < 4; ++k) {
        if (!neighbours_ok(i, k)) continue;
        const std::size_t j = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(i) + step[k]);
        if (!crack[j] && label[j] > 0 && fragment_of[static_cast<std::size_t>(label[j])] >= 0) {
          claim(i, label[j]);
          break;
        }
      }
    }
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::size_t i = queue[head];
      for (int k = 0; k < 4; ++k) {
        if (!neighbours_ok(i, k)) continue;
        const std::size_t j = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(i) + step[k]);
        if (crack[j] && label[j] <= 0 && mask.inside(static_cast<std::int64_t>(j))) claim(j, label[i]);
      }
    }
  }
  return fragments;
}

}  // namespace fissure::detail
