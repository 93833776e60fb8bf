#include "image_codecs.hpp"

#include "fissure/base/error.hpp"

#include <cstdio>  // jpeglib.h needs FILE
#include <csetjmp>

#include <jerror.h>
#include <jpeglib.h>

namespace fissure::detail {
namespace {

// libjpeg's error manager extended with a jump target and the first warning: error_exit would
// print and exit(), output_message would print to stderr; both are replaced.
struct JpegContext {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char error[JMSG_LENGTH_MAX] = {};
  char warning[JMSG_LENGTH_MAX] = {};
  int warning_code = 0;
  bool has_warning = false;
};

void on_error(j_common_ptr cinfo) {
  auto* context = reinterpret_cast<JpegContext*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, context->error);
  std::longjmp(context->jump, 1);
}

// Level −1 is a warning: corrupt or missing data that libjpeg papers over with grey blocks (a
// truncated file decodes "successfully" with a warning). Kept, never printed; trace messages
// (level ≥ 0) are dropped.
void on_message(j_common_ptr cinfo, int level) {
  auto* context = reinterpret_cast<JpegContext*>(cinfo->err);
  if (level >= 0 || context->has_warning) return;
  context->has_warning = true;
  context->warning_code = cinfo->err->msg_code;
  (*cinfo->err->format_message)(cinfo, context->warning);
}

void on_output(j_common_ptr) {}

enum class Status { Ok, Failed, TooLarge };

Status decode_into(JpegContext& context, std::string_view bytes, DecodedImage& image, std::int64_t max_pixels,
                   std::vector<std::uint8_t>& row) {
  jpeg_decompress_struct cinfo;
  cinfo.err = jpeg_std_error(&context.manager);
  context.manager.error_exit = on_error;
  context.manager.emit_message = on_message;
  context.manager.output_message = on_output;
  if (setjmp(context.jump)) {
    jpeg_destroy_decompress(&cinfo);
    return Status::Failed;
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&cinfo, TRUE);
  image.width = static_cast<int>(cinfo.image_width);
  image.height = static_cast<int>(cinfo.image_height);
  if (static_cast<std::int64_t>(cinfo.image_width) * cinfo.image_height > max_pixels) {
    jpeg_destroy_decompress(&cinfo);
    return Status::TooLarge;
  }
  // Grey is the luma channel of YCbCr; CMYK (Adobe, stored inverted) cannot be converted by
  // libjpeg and is converted below.
  const bool cmyk = cinfo.jpeg_color_space == JCS_CMYK || cinfo.jpeg_color_space == JCS_YCCK;
  cinfo.out_color_space = cmyk ? JCS_CMYK : JCS_GRAYSCALE;
  jpeg_start_decompress(&cinfo);
  const std::size_t width = cinfo.output_width;
  const int components = cinfo.output_components;
  image.grey.assign(width * cinfo.output_height, 0);
  row.assign(width * static_cast<std::size_t>(components), 0);
  while (cinfo.output_scanline < cinfo.output_height) {
    const std::size_t y = cinfo.output_scanline;
    JSAMPROW rows[1] = {row.data()};
    jpeg_read_scanlines(&cinfo, rows, 1);
    std::uint8_t* grey = image.grey.data() + y * width;
    if (components == 1) {
      for (std::size_t x = 0; x < width; ++x) grey[x] = row[x];
    } else {
      for (std::size_t x = 0; x < width; ++x) {
        const unsigned c = row[4 * x], m = row[4 * x + 1], ye = row[4 * x + 2], k = row[4 * x + 3];
        grey[x] = grey_of(c * k / 255, m * k / 255, ye * k / 255);
      }
    }
  }
  // Reads to the EOI marker; bytes after it (cameras and editors append some) are never read.
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  return Status::Ok;
}

}  // namespace

DecodedImage decode_jpeg(std::string_view bytes, const std::string& name, std::int64_t max_pixels) {
  JpegContext context;
  DecodedImage image;
  std::vector<std::uint8_t> row;
  const Status status = decode_into(context, bytes, image, max_pixels, row);
  if (status == Status::TooLarge) check_image_size(name, image.width, image.height, max_pixels);
  if (status != Status::Ok) throw IoError(name + ": cannot decode the JPEG image: " + context.error);
  // A warning means libjpeg filled in what the file lacks: a truncated or damaged image, refused
  // rather than analysed with grey blocks in it.
  if (context.has_warning) {
    if (context.warning_code == JWRN_JPEG_EOF) throw IoError(name + ": the JPEG image is truncated (it ends before its EOI marker)");
    throw IoError(name + ": the JPEG image is corrupt (" + std::string(context.warning) + ")");
  }
  check_image_size(name, image.width, image.height, max_pixels);
  return image;
}

}  // namespace fissure::detail
