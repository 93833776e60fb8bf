#include "bgr_png.hpp"

#include "fissure/base/atomic_file.hpp"

#include "image_codecs.hpp"

#include <cstdint>
#include <vector>

namespace fissure::detail {

void write_bgr_png(const std::filesystem::path& path, const cv::Mat& bgr) {
  CV_Assert(bgr.type() == CV_8UC3);
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(bgr.cols) * bgr.rows * 3);
  for (int y = 0; y < bgr.rows; ++y) {
    const cv::Vec3b* row = bgr.ptr<cv::Vec3b>(y);
    std::uint8_t* out = rgb.data() + static_cast<std::size_t>(y) * bgr.cols * 3;
    for (int x = 0; x < bgr.cols; ++x) {
      out[3 * x] = row[x][2];
      out[3 * x + 1] = row[x][1];
      out[3 * x + 2] = row[x][0];
    }
  }
  write_file_atomically(path, encode_png_rgb(rgb, bgr.cols, bgr.rows, path.string()));
}

}  // namespace fissure::detail
