#pragma once
// Image file decoding and PNG encoding with the codec libraries called directly (libpng,
// libjpeg-turbo, libtiff, and Fissure's own BMP reader), each with its error and warning handlers
// installed: nothing reaches stderr, every failure is an IoError naming the file, and no pixel
// buffer is allocated before the header's size has been checked against the limit. Private to
// the exemplar module.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace fissure::detail {

/// 8-bit grey pixels (row-major) and, when the file has an alpha channel, its 8-bit opacity.
struct DecodedImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> grey;
  std::vector<std::uint8_t> alpha;  ///< empty without an alpha channel
};

enum class ImageFormat { Unknown, Png, Jpeg, Tiff, Bmp };

/// The format named by the file's first bytes (its signature), whatever its extension.
ImageFormat sniff_image_format(std::string_view bytes);

/// Throws InvalidInput "<name>: image is W x H = N megapixels, above the limit of M megapixels"
/// when width·height > max_pixels; IoError when a side is not positive.
void check_image_size(const std::string& name, std::int64_t width, std::int64_t height, std::int64_t max_pixels);

/// Grey level of an sRGB pixel with OpenCV's integer weights (0.299, 0.587, 0.114 in Q14), the
/// conversion the analysis used before it decoded images itself.
inline std::uint8_t grey_of(unsigned r, unsigned g, unsigned b) {
  return static_cast<std::uint8_t>((r * 4899u + g * 9617u + b * 1868u + (1u << 13)) >> 14);
}

/// Each decodes a whole file held in `bytes`; `name` is used in messages.
DecodedImage decode_png(std::string_view bytes, const std::string& name, std::int64_t max_pixels);
DecodedImage decode_jpeg(std::string_view bytes, const std::string& name, std::int64_t max_pixels);
DecodedImage decode_tiff(std::string_view bytes, const std::string& name, std::int64_t max_pixels);
DecodedImage decode_bmp(std::string_view bytes, const std::string& name, std::int64_t max_pixels);

/// An 8-bit RGB PNG of `rgb` (row-major, 3 bytes a pixel). Throws IoError naming `name`.
std::string encode_png_rgb(const std::vector<std::uint8_t>& rgb, int width, int height, const std::string& name);
/// An 8-bit greyscale PNG of `grey` (row-major, 1 byte a pixel). Throws IoError naming `name`.
std::string encode_png_grey(const std::vector<std::uint8_t>& grey, int width, int height, const std::string& name);

}  // namespace fissure::detail
