#include "fissure/exemplar/crack_image.hpp"

#include "image_codecs.hpp"

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

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
    // Signed (a negative height is a top-down bitmap); INT32_MIN has no absolute value in int.
    const std::int64_t w = static_cast<std::int32_t>(little_endian_32(&head[18]));
    const std::int64_t h = static_cast<std::int32_t>(little_endian_32(&head[22]));
    auto side = [](std::int64_t v) { return static_cast<int>(std::min<std::int64_t>(v < 0 ? -v : v, INT32_MAX)); };
    return {side(w), side(h)};
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

std::vector<std::string> GreyImage::problems() const {
  std::vector<std::string> out;
  if (width < 0 || height < 0) out.push_back("size " + std::to_string(width) + " x " + std::to_string(height) + " is negative");
  const std::int64_t expected = static_cast<std::int64_t>(std::max(width, 0)) * std::max(height, 0);
  if (static_cast<std::int64_t>(pixels.size()) != expected) {
    out.push_back("holds " + std::to_string(pixels.size()) + " pixels, not " + std::to_string(width) + " x " +
                  std::to_string(height) + " = " + std::to_string(expected));
  }
  return out;
}

std::vector<std::string> CrackImageOptions::problems() const {
  std::vector<std::string> out;
  if (polarity != CrackPolarity::Auto && polarity != CrackPolarity::LightOnDark && polarity != CrackPolarity::DarkOnLight) {
    out.push_back("polarity " + std::to_string(static_cast<int>(polarity)) + " is not auto, light or dark");
  }
  if (threshold < -1 || threshold > 255) {
    out.push_back("threshold " + std::to_string(threshold) + " is outside [0, 255] (or -1 for Otsu's method)");
  }
  if (max_pixels <= 0) out.push_back("max_pixels " + std::to_string(max_pixels) + " is not positive");
  return out;
}

void CrackImageOptions::validate() const { throw_if_problems("crack image options", problems()); }

namespace detail {

ImageFormat sniff_image_format(std::string_view b) {
  auto starts = [&](std::string_view signature) { return b.substr(0, signature.size()) == signature; };
  if (starts("\x89PNG\r\n\x1a\n")) return ImageFormat::Png;
  if (starts("\xFF\xD8\xFF")) return ImageFormat::Jpeg;
  if (starts(std::string_view("II*\0", 4)) || starts(std::string_view("MM\0*", 4))) return ImageFormat::Tiff;
  if (starts("BM")) return ImageFormat::Bmp;
  return ImageFormat::Unknown;
}

void check_image_size(const std::string& name, std::int64_t width, std::int64_t height, std::int64_t max_pixels) {
  if (width <= 0 || height <= 0) {
    throw IoError(name + ": cannot decode the image: its header gives a size of " + std::to_string(width) + " x " +
                  std::to_string(height));
  }
  const std::int64_t pixels = width * height;
  if (pixels > max_pixels) {
    throw InvalidInput(name + ": image is " + std::to_string(width) + " x " + std::to_string(height) + " = " +
                       format_number(static_cast<double>(pixels) / 1e6, 3) + " megapixels, above the limit of " +
                       format_number(static_cast<double>(max_pixels) / 1e6, 3) + " megapixels");
  }
}

}  // namespace detail

GreyImage load_grey_image(const fs::path& path, std::int64_t max_pixels) {
  const std::string name = path.string();
  if (max_pixels <= 0) throw InvalidInput(name + ": the pixel limit " + std::to_string(max_pixels) + " is not positive");
  // The header first, so that a huge image is refused before its file is even read.
  const auto [w, h] = image_size_from_header(path);
  if (w > 0 && h > 0) detail::check_image_size(name, w, h, max_pixels);
  const std::string bytes = read_file(path);
  detail::DecodedImage decoded;
  switch (detail::sniff_image_format(bytes)) {
    case detail::ImageFormat::Png: decoded = detail::decode_png(bytes, name, max_pixels); break;
    case detail::ImageFormat::Jpeg: decoded = detail::decode_jpeg(bytes, name, max_pixels); break;
    case detail::ImageFormat::Tiff: decoded = detail::decode_tiff(bytes, name, max_pixels); break;
    case detail::ImageFormat::Bmp: decoded = detail::decode_bmp(bytes, name, max_pixels); break;
    case detail::ImageFormat::Unknown: throw IoError(name + ": cannot decode the image: not a PNG, JPEG, TIFF or BMP file");
  }
  GreyImage image;
  image.width = decoded.width;
  image.height = decoded.height;
  const auto [lo, hi] = std::minmax_element(decoded.alpha.begin(), decoded.alpha.end());
  const bool alpha_carries_drawing = !decoded.alpha.empty() && *lo != *hi;
  image.pixels = alpha_carries_drawing ? std::move(decoded.alpha) : std::move(decoded.grey);
  return image;
}

void write_grey_png(const fs::path& path, const GreyImage& image) {
  const std::string name = path.string();
  const std::vector<std::string> problems = image.problems();
  if (!problems.empty()) throw InvalidInput(name + ": cannot write the image: it " + problems.front());
  if (image.width < 1 || image.height < 1) throw InvalidInput(name + ": cannot write an empty image");
  write_file_atomically(path, detail::encode_png_grey(image.pixels, image.width, image.height, name));
}

CrackMask crack_mask_from_grey(const GreyImage& image, const CrackImageOptions& options, const std::string& name) {
  options.validate();
  throw_if_problems(name + ": image", image.problems());
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
  options.validate();
  CrackMask mask = crack_mask_from_grey(load_grey_image(path, options.max_pixels), options, path.string());
  if (!options.roi_path.empty()) {
    const GreyImage roi = load_grey_image(options.roi_path, options.max_pixels);
    if (roi.width != mask.width || roi.height != mask.height) {
      throw InvalidInput(options.roi_path.string() + ": region-of-interest mask is " + std::to_string(roi.width) + " x " +
                         std::to_string(roi.height) + ", the image " + path.string() + " is " + std::to_string(mask.width) +
                         " x " + std::to_string(mask.height));
    }
    mask.roi.resize(mask.crack.size());
    std::size_t inside = 0;
    for (std::size_t i = 0; i < roi.pixels.size(); ++i) {
      mask.roi[i] = roi.pixels[i] != 0;
      inside += mask.roi[i];
    }
    if (inside == 0) throw InvalidInput(options.roi_path.string() + ": region-of-interest mask is empty");
  }
  return mask;
}

}  // namespace fissure
