#include "image_codecs.hpp"

#include "fissure/base/error.hpp"

#include <tiffio.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>

namespace fissure::detail {
namespace {

// The file in memory, read through libtiff's client interface; errors and warnings through
// per-handle handlers (libtiff ≥ 4.5), so nothing goes to stderr and threads do not share state.
struct TiffContext {
  std::string_view bytes;
  toff_t position = 0;
  std::string error;
};

tsize_t on_read(thandle_t handle, tdata_t out, tsize_t size) {
  auto* context = static_cast<TiffContext*>(handle);
  if (size <= 0 || context->position >= context->bytes.size()) return 0;
  const auto n = static_cast<tsize_t>(std::min<toff_t>(static_cast<toff_t>(size), context->bytes.size() - context->position));
  std::memcpy(out, context->bytes.data() + context->position, static_cast<std::size_t>(n));
  context->position += static_cast<toff_t>(n);
  return n;
}
tsize_t on_write(thandle_t, tdata_t, tsize_t) { return 0; }
toff_t on_seek(thandle_t handle, toff_t offset, int whence) {
  auto* context = static_cast<TiffContext*>(handle);
  const toff_t base = whence == SEEK_CUR ? context->position : whence == SEEK_END ? context->bytes.size() : 0;
  context->position = base + offset;
  return context->position;
}
int on_close(thandle_t) { return 0; }
toff_t on_size(thandle_t handle) { return static_cast<TiffContext*>(handle)->bytes.size(); }
int on_map(thandle_t, tdata_t*, toff_t*) { return 0; }
void on_unmap(thandle_t, tdata_t, toff_t) {}

int on_error(TIFF*, void* user_data, const char* module, const char* format, va_list arguments) {
  auto* context = static_cast<TiffContext*>(user_data);
  if (context->error.empty()) {
    char text[512];
    std::vsnprintf(text, sizeof text, format, arguments);
    context->error = text;
    for (char& c : context->error)
      if (c == '\n' || c == '\r') c = ' ';  // one line, whatever libtiff's format holds
  }
  return 1;  // handled: libtiff's global handler (stderr) is not called
}
// Warnings (unknown tags, odd but readable layouts) do not stop decoding: silenced.
int on_warning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

// Bounds any single allocation libtiff makes from header values (strip sizes, tag arrays): a
// corrupt header cannot make it ask for gigabytes. 256 MB is above any strip of a 64-megapixel
// tracing.
constexpr tmsize_t kMaxTiffAllocation = 256 * 1024 * 1024;

}  // namespace

DecodedImage decode_tiff(std::string_view bytes, const std::string& name, std::int64_t max_pixels) {
  TiffContext context;
  context.bytes = bytes;
  TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
  if (!options) throw IoError(name + ": cannot decode the TIFF image: out of memory");
  TIFFOpenOptionsSetErrorHandlerExtR(options, on_error, &context);
  TIFFOpenOptionsSetWarningHandlerExtR(options, on_warning, &context);
  TIFFOpenOptionsSetMaxSingleMemAlloc(options, kMaxTiffAllocation);
  TIFF* tiff = TIFFClientOpenExt(name.c_str(), "rm", &context, on_read, on_write, on_seek, on_close, on_size, on_map,
                                 on_unmap, options);
  TIFFOpenOptionsFree(options);
  auto fail = [&](const std::string& why) {
    if (tiff) TIFFClose(tiff);
    return IoError(name + ": cannot decode the TIFF image: " + (context.error.empty() ? why : context.error));
  };
  if (!tiff) throw fail("not a readable TIFF file");
  std::uint32_t width = 0, height = 0;
  if (!TIFFGetField(tiff, TIFFTAG_IMAGEWIDTH, &width) || !TIFFGetField(tiff, TIFFTAG_IMAGELENGTH, &height)) {
    throw fail("no image width or length");
  }
  if (static_cast<std::int64_t>(width) * height > max_pixels || width == 0 || height == 0) {
    TIFFClose(tiff);
    check_image_size(name, width, height, max_pixels);
  }
  char why[1024] = {};
  if (!TIFFRGBAImageOK(tiff, why)) throw fail(why);
  std::uint16_t extra = 0;
  std::uint16_t* extra_types = nullptr;
  const bool has_alpha = TIFFGetField(tiff, TIFFTAG_EXTRASAMPLES, &extra, &extra_types) && extra > 0 &&
                         (extra_types[0] == EXTRASAMPLE_ASSOCALPHA || extra_types[0] == EXTRASAMPLE_UNASSALPHA);
  // libtiff's RGBA interface reads every layout (strips, tiles, bit depths, palettes,
  // compressions) into 4 bytes a pixel: within the pixel limit, ≤ 256 MB at 64 megapixels.
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  std::vector<std::uint32_t> raster(pixels);
  if (!TIFFReadRGBAImageOriented(tiff, width, height, raster.data(), ORIENTATION_TOPLEFT, 1) || !context.error.empty()) {
    throw fail("damaged or truncated pixel data");
  }
  TIFFClose(tiff);
  DecodedImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.grey.resize(pixels);
  if (has_alpha) image.alpha.resize(pixels);
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint32_t p = raster[i];
    image.grey[i] = grey_of(TIFFGetR(p), TIFFGetG(p), TIFFGetB(p));
    if (has_alpha) image.alpha[i] = static_cast<std::uint8_t>(TIFFGetA(p));
  }
  return image;
}

}  // namespace fissure::detail
