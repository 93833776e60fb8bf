#include "image_codecs.hpp"

#include "fissure/base/error.hpp"

#include <array>
#include <bit>

namespace fissure::detail {
namespace {

std::uint32_t u32(std::string_view b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3])) << 24;
}
std::uint16_t u16(std::string_view b, std::size_t at) {
  return static_cast<std::uint16_t>(static_cast<unsigned char>(b[at]) | static_cast<unsigned char>(b[at + 1]) << 8);
}

// One channel of a bit-field pixel scaled to 8 bits (a 5-bit field's 31 becomes 255).
struct Field {
  std::uint32_t mask = 0;
  int shift = 0;
  std::uint32_t max = 0;
  explicit Field(std::uint32_t m = 0) : mask(m) {
    if (!mask) return;
    shift = std::countr_zero(mask);
    max = mask >> shift;
  }
  std::uint8_t operator()(std::uint32_t pixel) const {
    if (!mask) return 0;
    return static_cast<std::uint8_t>(static_cast<std::uint64_t>((pixel & mask) >> shift) * 255u / max);
  }
};

}  // namespace

// A strict reader of the uncompressed Windows bitmap: BITMAPCOREHEADER (12 bytes) and
// BITMAPINFOHEADER and its V2–V5 extensions (40–124 bytes); 1, 4 and 8 bits a pixel with a
// palette, 16 and 32 with bit fields (or 5-5-5 / 8-8-8-x by default), 24 as BGR; bottom-up or
// top-down. Every size is checked against the file before anything is read or allocated.
// Run-length and embedded JPEG/PNG bitmaps are refused (rare for tracings; say so rather than
// guess).
DecodedImage decode_bmp(std::string_view b, const std::string& name, std::int64_t max_pixels) {
  auto corrupt = [&](const std::string& why) { return IoError(name + ": cannot decode the BMP image: " + why); };
  if (b.size() < 26 || b[0] != 'B' || b[1] != 'M') throw corrupt("not a BMP file");
  const std::uint32_t pixel_offset = u32(b, 10);
  const std::uint32_t header = u32(b, 14);
  if (header != 12 && header != 40 && header != 52 && header != 56 && header != 108 && header != 124) {
    throw corrupt("unknown header size " + std::to_string(header));
  }
  if (14 + static_cast<std::uint64_t>(header) > b.size()) throw corrupt("the file ends inside its header (truncated)");
  std::int64_t width = 0, height = 0;
  int bits = 0;
  std::uint32_t compression = 0, colours_used = 0;
  if (header == 12) {
    width = u16(b, 18);
    height = static_cast<std::int16_t>(u16(b, 20));
    if (u16(b, 22) != 1) throw corrupt("plane count is not 1");
    bits = u16(b, 24);
  } else {
    width = static_cast<std::int32_t>(u32(b, 18));
    height = static_cast<std::int32_t>(u32(b, 22));
    if (u16(b, 26) != 1) throw corrupt("plane count is not 1");
    bits = u16(b, 28);
    compression = u32(b, 30);
    colours_used = u32(b, 46);
  }
  const bool top_down = height < 0;
  if (top_down) height = -height;
  if (width <= 0 || height <= 0) throw corrupt("image is " + std::to_string(width) + " x " + std::to_string(height));
  check_image_size(name, width, height, max_pixels);
  // Bit fields: after a 40-byte header (3 masks, or 4 with BI_ALPHABITFIELDS), inside V2+ headers.
  std::uint32_t masks[4] = {0, 0, 0, 0};
  bool fields = false;
  if (compression == 3 || compression == 6) {
    if (bits != 16 && bits != 32) throw corrupt("bit fields with " + std::to_string(bits) + " bits a pixel");
    const std::size_t count = header >= 56 || compression == 6 ? 4 : 3;
    if (14 + 40 + 4 * count > b.size()) throw corrupt("the file ends inside its colour masks (truncated)");
    for (std::size_t k = 0; k < count; ++k) masks[k] = u32(b, 14 + 40 + 4 * k);
    fields = true;
  } else if (compression == 1 || compression == 2) {
    throw corrupt("run-length compressed bitmaps are not supported (save it uncompressed or as PNG)");
  } else if (compression != 0) {
    throw corrupt("compression type " + std::to_string(compression) + " is not supported");
  } else if (header >= 56 && bits == 32 && u32(b, 14 + 52) != 0) {
    masks[3] = u32(b, 14 + 52);  // a V3+ header may name an alpha mask for plain 32-bit pixels
  }
  if (bits != 1 && bits != 4 && bits != 8 && bits != 16 && bits != 24 && bits != 32) {
    throw corrupt(std::to_string(bits) + " bits a pixel");
  }
  // The palette, as grey levels.
  std::vector<std::uint8_t> palette;
  if (bits <= 8) {
    const std::size_t entry = header == 12 ? 3 : 4;
    const std::size_t count = colours_used ? colours_used : std::size_t{1} << bits;
    if (count > (std::size_t{1} << bits)) throw corrupt(std::to_string(count) + " palette colours for " + std::to_string(bits) + "-bit pixels");
    const std::size_t start = 14 + header;
    if (start + count * entry > b.size()) throw corrupt("the file ends inside its palette (truncated)");
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t at = start + k * entry;
      palette.push_back(grey_of(static_cast<unsigned char>(b[at + 2]), static_cast<unsigned char>(b[at + 1]),
                                static_cast<unsigned char>(b[at])));
    }
  }
  const std::uint64_t stride = (static_cast<std::uint64_t>(width) * bits + 31) / 32 * 4;
  if (pixel_offset < 14 + header || pixel_offset + stride * static_cast<std::uint64_t>(height) > b.size()) {
    throw corrupt("the pixel data is truncated (" + std::to_string(b.size()) + " bytes, " +
                  std::to_string(pixel_offset + stride * static_cast<std::uint64_t>(height)) + " needed)");
  }
  if (!fields && bits == 16) masks[0] = 0x7C00, masks[1] = 0x03E0, masks[2] = 0x001F;
  if (!fields && bits == 32) masks[0] = 0x00FF0000, masks[1] = 0x0000FF00, masks[2] = 0x000000FF;
  const Field red(masks[0]), green(masks[1]), blue(masks[2]), alpha(masks[3]);
  DecodedImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  const std::size_t w = static_cast<std::size_t>(width);
  image.grey.resize(w * static_cast<std::size_t>(height));
  if (alpha.mask) image.alpha.resize(image.grey.size());
  for (std::int64_t row = 0; row < height; ++row) {
    const std::size_t y = static_cast<std::size_t>(top_down ? row : height - 1 - row);
    const std::string_view line = b.substr(pixel_offset + static_cast<std::size_t>(stride) * static_cast<std::size_t>(row));
    std::uint8_t* grey = image.grey.data() + y * w;
    for (std::size_t x = 0; x < w; ++x) {
      if (bits <= 8) {
        const std::size_t bit = x * static_cast<std::size_t>(bits);
        const unsigned byte = static_cast<unsigned char>(line[bit / 8]);
        const unsigned index = (byte >> (8 - bits - bit % 8)) & ((1u << bits) - 1u);
        if (index >= palette.size()) {
          throw corrupt("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") names colour " + std::to_string(index) +
                        " of a " + std::to_string(palette.size()) + "-colour palette");
        }
        grey[x] = palette[index];
      } else if (bits == 24) {
        const std::size_t at = 3 * x;
        grey[x] = grey_of(static_cast<unsigned char>(line[at + 2]), static_cast<unsigned char>(line[at + 1]),
                          static_cast<unsigned char>(line[at]));
      } else {
        const std::uint32_t pixel = bits == 16 ? u16(line, 2 * x) : u32(line, 4 * x);
        grey[x] = grey_of(red(pixel), green(pixel), blue(pixel));
        if (alpha.mask) image.alpha[y * w + x] = alpha(pixel);
      }
    }
  }
  return image;
}

}  // namespace fissure::detail
