#include "image_codecs.hpp"

#include "fissure/base/error.hpp"

#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstring>

namespace fissure::detail {
namespace {

// Everything the C callbacks touch lives here, outside the frames that png_longjmp skips, so no
// C++ destructor is ever jumped over.
struct PngContext {
  std::string_view bytes;
  std::size_t position = 0;
  std::string error;
  std::string warning;  // the last one: libpng explains an "Invalid IHDR data" error in warnings
  std::string output;   // encoding
};

void on_error(png_structp png, png_const_charp message) {
  auto* context = static_cast<PngContext*>(png_get_error_ptr(png));
  context->error = message ? message : "unknown libpng error";
  png_longjmp(png, 1);
}

// libpng's warnings concern ancillary data (colour profiles, text chunks) that the analysis never
// reads, or explain the error that follows: kept for that message, never printed.
void on_warning(png_structp png, png_const_charp message) {
  static_cast<PngContext*>(png_get_error_ptr(png))->warning = message ? message : "";
}

void on_read(png_structp png, png_bytep out, png_size_t length) {
  auto* context = static_cast<PngContext*>(png_get_io_ptr(png));
  if (context->bytes.size() - context->position < length) png_error(png, "the file ends early (truncated)");
  std::memcpy(out, context->bytes.data() + context->position, length);
  context->position += length;
}

void on_write(png_structp png, png_bytep data, png_size_t length) {
  static_cast<PngContext*>(png_get_io_ptr(png))->output.append(reinterpret_cast<const char*>(data), length);
}
void on_flush(png_structp) {}

enum class Status { Ok, Failed, TooLarge };

// The decoding proper, in a function with only trivially destructible locals (setjmp rules).
Status decode_into(PngContext& context, DecodedImage& image, std::int64_t max_pixels, std::vector<std::uint8_t>& row) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &context, on_error, on_warning);
  if (!png) {
    context.error = "out of memory";
    return Status::Failed;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    context.error = "out of memory";
    return Status::Failed;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return Status::Failed;
  }
  png_set_read_fn(png, &context, on_read);
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info), height = png_get_image_height(png, info);
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  if (static_cast<std::int64_t>(width) * height > max_pixels) {
    png_destroy_read_struct(&png, &info, nullptr);
    return Status::TooLarge;
  }
  // To 8 bits a sample, grey or RGB, with alpha when the file has any (tRNS included).
  png_set_expand(png);
  png_set_strip_16(png);
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const int channels = png_get_channels(png, info);
  const std::size_t row_bytes = png_get_rowbytes(png, info);
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  const bool has_alpha = channels == 2 || channels == 4;
  image.grey.assign(pixels, 0);
  if (has_alpha) image.alpha.assign(pixels, 255);
  // Non-interlaced files are converted row by row; interlaced ones need the whole image first.
  row.assign(passes > 1 ? row_bytes * height : row_bytes, 0);
  auto convert = [&](const png_byte* in, std::size_t y) {
    std::uint8_t* grey = image.grey.data() + y * width;
    std::uint8_t* alpha = has_alpha ? image.alpha.data() + y * width : nullptr;
    for (png_uint_32 x = 0; x < width; ++x, in += channels) {
      grey[x] = channels >= 3 ? grey_of(in[0], in[1], in[2]) : in[0];
      if (alpha) alpha[x] = in[channels - 1];
    }
  };
  if (passes > 1) {
    for (int pass = 0; pass < passes; ++pass)
      for (png_uint_32 y = 0; y < height; ++y) png_read_row(png, row.data() + y * row_bytes, nullptr);
    for (png_uint_32 y = 0; y < height; ++y) convert(row.data() + y * row_bytes, y);
  } else {
    for (png_uint_32 y = 0; y < height; ++y) {
      png_read_row(png, row.data(), nullptr);
      convert(row.data(), y);
    }
  }
  // Up to IEND: a file cut after its pixel data is still truncated. Bytes after IEND (cameras and
  // editors append some) are never read.
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return Status::Ok;
}

// `channels` 1 (grey) or 3 (RGB), 8 bits a sample.
Status encode_into(PngContext& context, const std::vector<std::uint8_t>& samples, int width, int height, int channels) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &context, on_error, on_warning);
  if (!png) {
    context.error = "out of memory";
    return Status::Failed;
  }
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    if (context.error.empty()) context.error = "out of memory";
    return Status::Failed;
  }
  png_set_write_fn(png, &context, on_write, on_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               channels == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) {
    png_write_row(png, samples.data() + static_cast<std::size_t>(y) * width * channels);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return Status::Ok;
}

}  // namespace

DecodedImage decode_png(std::string_view bytes, const std::string& name, std::int64_t max_pixels) {
  PngContext context;
  context.bytes = bytes;
  DecodedImage image;
  std::vector<std::uint8_t> row;
  const Status status = decode_into(context, image, max_pixels, row);
  if (status == Status::TooLarge) check_image_size(name, image.width, image.height, max_pixels);
  if (status != Status::Ok) {
    throw IoError(name + ": cannot decode the PNG image: " + context.error +
                  (context.warning.empty() ? "" : " (" + context.warning + ")"));
  }
  return image;
}

namespace {

std::string encode_png(const std::vector<std::uint8_t>& samples, int width, int height, int channels, const std::string& name) {
  if (width <= 0 || height <= 0 || samples.size() != static_cast<std::size_t>(width) * height * channels) {
    throw IoError(name + ": cannot encode a " + std::to_string(width) + " x " + std::to_string(height) + " PNG from " +
                  std::to_string(samples.size()) + " bytes");
  }
  PngContext context;
  if (encode_into(context, samples, width, height, channels) != Status::Ok) {
    throw IoError(name + ": cannot encode the PNG image: " + context.error);
  }
  return std::move(context.output);
}

}  // namespace

std::string encode_png_rgb(const std::vector<std::uint8_t>& rgb, int width, int height, const std::string& name) {
  return encode_png(rgb, width, height, 3, name);
}

std::string encode_png_grey(const std::vector<std::uint8_t>& grey, int width, int height, const std::string& name) {
  return encode_png(grey, width, height, 1, name);
}

}  // namespace fissure::detail
