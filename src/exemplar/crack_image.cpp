#include "fissure/exemplar/crack_image.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>

namespace fissure {
namespace fs = std::filesystem;
namespace {

std::uint32_t big_endian_32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}
std::uint16_t big_endian_16(const unsigned char* p) { return static_cast<std::uint16_t>((p[0] << 8) | p[1]); }
std::uint32_t little_endian_32(const unsigned char* p) {
  return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24);
}
std::uint16_t little_endian_16(const unsigned char* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }

// Otsu's threshold on a 256-bin histogram: the level maximising the between-class variance.
int otsu_threshold(const std::vector<std::uint8_t>& pixels) {
  std::array<double, 256> hist{};
  for (std::uint8_t v : pixels) hist[v] += 1.0;
  const double total = static_cast<double>(pixels.size());
  double sum = 0.0;
  for (int i = 0; i < 256; ++i) sum += i * hist[static_cast<std::size_t>(i)];
  double weight_below = 0.0, sum_below = 0.0, best = -1.0;
  int level = 128;
  for (int t = 0; t < 255; ++t) {
    weight_below += hist[static_cast<std::size_t>(t)];
    sum_below += t * hist[static_cast<std::size_t>(t)];
    const double weight_above = total - weight_below;
    if (weight_below == 0.0 || weight_above == 0.0) continue;
    const double mean_below = sum_below / weight_below;
    const double mean_above = (sum - sum_below) / weight_above;
    const double between = weight_below * weight_above * (mean_below - mean_above) * (mean_below - mean_above);
    if (between > best) {
      best = between;
      level = t + 1;  // pixels ≥ level are "light"
    }
  }
  return level;
}

GreyImage to_grey(const cv::Mat& image) {
  cv::Mat grey;
  if (image.channels() == 1) {
    grey = image;
  } else if (image.channels() == 4) {
    cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
  } else {
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  }
  if (grey.depth() != CV_8U) {
    double lo = 0, hi = 0;
    cv::minMaxLoc(grey, &lo, &hi);
    cv::Mat scaled;
    grey.convertTo(scaled, CV_8U, hi > lo ? 255.0 / (hi - lo) : 1.0, hi > lo ? -lo * 255.0 / (hi - lo) : 0.0);
    grey = scaled;
  }
  GreyImage out;
  out.width = grey.cols;
  out.height = grey.rows;
  out.pixels.resize(static_cast<std::size_t>(grey.total()));
  for (int y = 0; y < grey.rows; ++y) std::memcpy(out.pixels.data() + static_cast<std::size_t>(y) * grey.cols, grey.ptr(y), grey.cols);
  return out;
}

cv::Mat decode(const fs::path& path, const CrackImageOptions& options, int flags) {
  const std::string name = path.string();
  const auto [w, h] = image_size_from_header(path);
  if (w >= 0) {
    const std::int64_t pixels = static_cast<std::int64_t>(w) * h;
    if (pixels > options.max_pixels) {
      throw InvalidInput(name + ": image is " + std::to_string(w) + " x " + std::to_string(h) + " = " +
                         std::to_string(pixels / 1'000'000) + " megapixels, above the limit of " +
                         std::to_string(options.max_pixels / 1'000'000) +
                         " megapixels (raise it with --max-megapixels)");
    }
  }
  // A PNG must end with its IEND chunk and a JPEG with the EOI marker: checking first gives a
  // clear message for a truncated file (libpng would print its own error to the terminal).
  {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    const auto size = static_cast<std::streamoff>(in.tellg());
    unsigned char head[4] = {}, tail[12] = {};
    in.seekg(0);
    in.read(reinterpret_cast<char*>(head), 4);
    if (size >= 12) {
      in.seekg(size - 12);
      in.read(reinterpret_cast<char*>(tail), 12);
    }
    const bool png = head[0] == 0x89 && head[1] == 'P' && head[2] == 'N' && head[3] == 'G';
    const bool jpeg = head[0] == 0xFF && head[1] == 0xD8;
    if ((png && std::memcmp(tail + 4, "IEND", 4) != 0) || (jpeg && !(tail[10] == 0xFF && tail[11] == 0xD9))) {
      throw IoError(name + ": the image file is truncated");
    }
  }
  cv::Mat image;
  try {
    image = cv::imread(name, flags);
  } catch (const cv::Exception& e) {
    throw IoError(name + ": cannot decode the image: " + e.what());
  }
  if (image.empty()) throw IoError(name + ": cannot decode the image (corrupt, truncated or not PNG/JPEG/TIFF/BMP)");
  return image;
}

}  // namespace

std::pair<int, int> image_size_from_header(const fs::path& path) {
  require_nonempty_file(path);
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> head(64 * 1024);
  in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
  const std::size_t n = static_cast<std::size_t>(in.gcount());
  head.resize(n);
  if (n >= 24 && std::memcmp(head.data(), "\x89PNG\r\n\x1a\n", 8) == 0) {
    return {static_cast<int>(big_endian_32(&head[16])), static_cast<int>(big_endian_32(&head[20]))};
  }
  if (n >= 26 && head[0] == 'B' && head[1] == 'M') {
    const int w = static_cast<int>(little_endian_32(&head[18]));
    const int h = static_cast<int>(little_endian_32(&head[22]));
    return {std::abs(w), std::abs(h)};
  }
  if (n >= 4 && head[0] == 0xFF && head[1] == 0xD8) {
    // Walk the JPEG markers to the first start-of-frame.
    std::size_t i = 2;
    while (i + 9 < n) {
      if (head[i] != 0xFF) return {-1, -1};
      const unsigned char marker = head[i + 1];
      const std::size_t length = big_endian_16(&head[i + 2]);
      if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC) {
        return {big_endian_16(&head[i + 7]), big_endian_16(&head[i + 5])};
      }
      i += 2 + length;
    }
    return {-1, -1};
  }
  if (n >= 8 && ((head[0] == 'I' && head[1] == 'I') || (head[0] == 'M' && head[1] == 'M'))) {
    const bool le = head[0] == 'I';
    auto u16 = [&](std::size_t at) { return le ? little_endian_16(&head[at]) : big_endian_16(&head[at]); };
    auto u32 = [&](std::size_t at) { return le ? little_endian_32(&head[at]) : big_endian_32(&head[at]); };
    const std::size_t ifd = u32(4);
    if (ifd + 2 > n) return {-1, -1};
    const std::size_t entries = u16(ifd);
    int w = -1, h = -1;
    for (std::size_t e = 0; e < entries && ifd + 2 + 12 * (e + 1) <= n; ++e) {
      const std::size_t at = ifd + 2 + 12 * e;
      const int tag = u16(at), type = u16(at + 2);
      const int value = type == 3 ? u16(at + 8) : static_cast<int>(u32(at + 8));
      if (tag == 256) w = value;
      if (tag == 257) h = value;
    }
    return {w, h};
  }
  return {-1, -1};
}

CrackMask crack_mask_from_grey(const GreyImage& image, const CrackImageOptions& options, const std::string& name) {
  if (image.width < kMinImageSide || image.height < kMinImageSide) {
    throw InvalidInput(name + ": image is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                       ", smaller than the " + std::to_string(kMinImageSide) + " x " + std::to_string(kMinImageSide) +
                       " needed to see a crack pattern");
  }
  CrackMask mask;
  mask.width = image.width;
  mask.height = image.height;
  mask.source = name;
  const auto [lo, hi] = std::minmax_element(image.pixels.begin(), image.pixels.end());
  if (*lo == *hi) {
    throw InvalidInput(name + ": image is blank (every pixel is " + std::to_string(*lo) +
                       "): no cracks to analyse, or nothing but crack");
  }
  mask.threshold = options.threshold >= 0 ? options.threshold : otsu_threshold(image.pixels);
  std::size_t light = 0;
  for (std::uint8_t v : image.pixels) light += v >= mask.threshold;
  switch (options.polarity) {
    case CrackPolarity::LightOnDark: mask.light_cracks = true; break;
    case CrackPolarity::DarkOnLight: mask.light_cracks = false; break;
    case CrackPolarity::Auto: mask.light_cracks = 2 * light <= image.pixels.size(); break;
  }
  mask.crack.resize(image.pixels.size());
  std::size_t cracks = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    mask.crack[i] = (image.pixels[i] >= mask.threshold) == mask.light_cracks;
    cracks += mask.crack[i];
  }
  if (cracks == 0) throw InvalidInput(name + ": no crack pixels at threshold " + std::to_string(mask.threshold));
  if (cracks == mask.crack.size()) throw InvalidInput(name + ": every pixel is crack: nothing is fractured into pieces");
  return mask;
}

CrackMask load_crack_mask(const fs::path& path, const CrackImageOptions& options) {
  // Decoded straight to 8-bit grey: a colour copy of a 4096² tracing would cost 50 MB.
  const cv::Mat image = decode(path, options, cv::IMREAD_GRAYSCALE);
  CrackMask mask = crack_mask_from_grey(to_grey(image), options, path.string());
  if (!options.roi_path.empty()) {
    const cv::Mat roi = decode(options.roi_path, options, cv::IMREAD_GRAYSCALE);
    if (roi.cols != mask.width || roi.rows != mask.height) {
      throw InvalidInput(options.roi_path.string() + ": region-of-interest mask is " + std::to_string(roi.cols) + " x " +
                         std::to_string(roi.rows) + ", the image " + path.string() + " is " + std::to_string(mask.width) +
                         " x " + std::to_string(mask.height));
    }
    mask.roi.resize(mask.crack.size());
    std::size_t inside = 0;
    for (int y = 0; y < roi.rows; ++y)
      for (int x = 0; x < roi.cols; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * mask.width + x;
        mask.roi[i] = roi.at<std::uint8_t>(y, x) != 0;
        inside += mask.roi[i];
      }
    if (inside == 0) throw InvalidInput(options.roi_path.string() + ": region-of-interest mask is empty");
  }
  return mask;
}

}  // namespace fissure
