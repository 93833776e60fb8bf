#pragma once
/// A traced crack image (paper §3: the cracks of a photograph, drawn by a user as lines) turned
/// into a binary crack mask: any polarity, greyscale or colour, anti-aliased or binary, with an
/// optional region-of-interest mask for the fractured area.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fissure {

/// 8-bit greyscale pixels, row-major (index y·width + x).
struct GreyImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;
  /// Readable problems (negative sides, pixels.size() ≠ width·height), empty when consistent.
  std::vector<std::string> problems() const;
};

enum class CrackPolarity {
  Auto,          ///< cracks are the minority class (lines cover less than half of a tracing)
  LightOnDark,   ///< white cracks on black
  DarkOnLight,   ///< black cracks on white
};

struct CrackImageOptions {
  CrackPolarity polarity = CrackPolarity::Auto;
  /// Grey level separating crack from background; −1 chooses it by Otsu's method, which suits
  /// anti-aliased and JPEG-compressed tracings as well as binary ones.
  int threshold = -1;
  /// Images above this many pixels are refused before they are decoded (raise it on purpose:
  /// a 4096² analysis peaks near 200 MB).
  std::int64_t max_pixels = 64'000'000;
  /// Optional mask of the fractured area, same size as the image; non-zero = inside.
  std::filesystem::path roi_path;

  /// Readable problems (an unknown polarity, a threshold outside [−1, 255], max_pixels ≤ 0),
  /// empty when valid. Each names the field.
  std::vector<std::string> problems() const;
  /// Throws InvalidInput "crack image options: <problems>" when problems() is not empty.
  void validate() const;
};

/// The binary result. crack[i] = 1 for crack pixels; roi empty = the whole image.
struct CrackMask {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> crack;
  std::vector<std::uint8_t> roi;
  std::string source;   ///< file name, for messages
  int threshold = 128;  ///< the grey level used
  bool light_cracks = true;

  std::int64_t pixel_count() const { return static_cast<std::int64_t>(width) * height; }
  bool inside(std::int64_t index) const { return roi.empty() || roi[static_cast<std::size_t>(index)] != 0; }
};

/// Smallest accepted side, pixels: below it no crack network can be seen.
constexpr int kMinImageSide = 8;

/// Width and height from the file header (PNG, JPEG, BMP, TIFF) without decoding; {−1, −1} when
/// the format is not one of those. Throws IoError for a missing or empty file.
std::pair<int, int> image_size_from_header(const std::filesystem::path& path);

/// Decodes an image file (PNG, JPEG, TIFF, BMP, recognised by content; any bit depth or channel
/// count) to 8-bit grey. Colour becomes luma (0.299 R + 0.587 G + 0.114 B). When the file has an
/// alpha channel that is not uniformly opaque, the drawing is in its opacity (a tracing layer
/// exported with a transparent background: the colour under transparent pixels is arbitrary), so
/// the alpha channel is returned as the grey image. Bytes after a PNG's IEND chunk or a JPEG's
/// EOI marker are ignored; a file that ends before them is truncated. Throws InvalidInput when
/// the header's width × height exceeds `max_pixels` (before any pixel is decoded), IoError naming
/// the file when it is missing, empty, of another format, truncated or corrupt. The codec
/// libraries' own messages never reach stderr. Memory: the file plus ≤ 2 bytes a pixel (4 for
/// TIFF). Safe to call from several threads.
GreyImage load_grey_image(const std::filesystem::path& path, std::int64_t max_pixels);

/// Writes `image` as an 8-bit greyscale PNG (libpng), atomically (base/atomic_file.hpp): what
/// load_grey_image reads back pixel for pixel. Throws InvalidInput when the image is
/// inconsistent or empty, IoError naming the file when it cannot be written.
void write_grey_png(const std::filesystem::path& path, const GreyImage& image);

/// Loads and binarises a tracing (load_grey_image, then crack_mask_from_grey). Throws IoError
/// naming the file when it is missing, empty, corrupt or undecodable, InvalidInput when it is too
/// small, larger than `max_pixels`, blank (no crack), all crack, when the ROI mask is missing or
/// of another size, or when `options` are invalid.
CrackMask load_crack_mask(const std::filesystem::path& path, const CrackImageOptions& options = {});

/// Binarises an in-memory image (tests, simulation renders). `name` is used in messages. Throws
/// InvalidInput when the image is inconsistent (pixels.size() ≠ width·height), too small, blank
/// or all crack, or when `options` are invalid.
CrackMask crack_mask_from_grey(const GreyImage& image, const CrackImageOptions& options, const std::string& name);

}  // namespace fissure
