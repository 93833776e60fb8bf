// Image decoding (libpng, libjpeg-turbo, libtiff and Fissure's BMP reader): valid files that the
// OpenCV path refused, truncations it missed or reported through the libraries' stderr lines,
// alpha-only tracings, and a fuzz test over corrupted files. Test images are encoded by OpenCV's
// imgcodecs, an independent encoder.

#include "fissure/base/atomic_file.hpp"
#include "fissure/base/error.hpp"
#include "fissure/base/rng.hpp"
#include "fissure/exemplar/exemplar_analysis.hpp"
#include "fissure/exemplar/stats_json.hpp"

#include "drawings.hpp"
#include "stderr_capture.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <chrono>
#include <cstring>
#include <fstream>

namespace fissure {
namespace {
namespace fs = std::filesystem;

std::string encode(const cv::Mat& image, const std::string& extension, const std::vector<int>& params = {}) {
  std::vector<std::uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(extension, image, bytes, params));
  return std::string(bytes.begin(), bytes.end());
}

// The error class and text of analysing `path`, "ok" when it succeeds.
std::string outcome(const fs::path& path) {
  try {
    analyze_exemplar(path);
    return "ok";
  } catch (const IoError& e) {
    return std::string("IoError: ") + e.what();
  } catch (const InvalidInput& e) {
    return std::string("InvalidInput: ") + e.what();
  }
}

const cv::Mat& drawing() {
  static const cv::Mat d = test::closed_grid_drawing(200, 4, 40, 3);
  return d;
}

std::string stats_of(const fs::path& path) { return pattern_stats_to_json(analyze_exemplar(path).stats); }

// Used to fail: "the image file is truncated" for a PNG followed by bytes after IEND and a JPEG
// by bytes after EOI (the check looked at the file's last bytes). Cameras and editors append
// such trailers; the image is whole and must give the same statistics.
TEST(ImageDecoding, BytesAfterTheEndMarkerAreIgnored) {
  const fs::path dir = test::fresh_temp_dir("exemplar-trailer");
  for (const char* extension : {".png", ".jpg"}) {
    SCOPED_TRACE(extension);
    const std::string bytes = encode(drawing(), extension, {cv::IMWRITE_JPEG_QUALITY, 95});
    const fs::path plain = dir / (std::string("plain") + extension), trailer = dir / (std::string("trailer") + extension);
    write_file_atomically(plain, bytes);
    static constexpr char kTrailer[] = "\0\0\0\0editor trailer: metadata after the end marker";
    write_file_atomically(trailer, bytes + std::string(kTrailer, sizeof kTrailer - 1));
    test::StderrCapture capture;
    const std::string a = stats_of(plain), b = stats_of(trailer);
    EXPECT_EQ(capture.finish(), "");
    EXPECT_EQ(a.substr(a.find("\"total_area\"")), b.substr(b.find("\"total_area\"")));
  }
}

// Real truncation is still caught, for every format, as an IoError naming the file, and no
// library line reaches stderr (a truncated TIFF or BMP used to print libtiff/OpenCV warnings).
TEST(ImageDecoding, TruncatedFilesAreRefusedQuietly) {
  const fs::path dir = test::fresh_temp_dir("exemplar-cut");
  for (const char* extension : {".png", ".jpg", ".tiff", ".bmp"}) {
    const std::string bytes = encode(drawing(), extension);
    for (const double keep : {0.3, 0.6, 0.9, 0.99}) {
      SCOPED_TRACE(std::string(extension) + " cut to " + std::to_string(keep));
      const fs::path path = dir / (std::string("cut") + extension);
      write_file_atomically(path, bytes.substr(0, static_cast<std::size_t>(static_cast<double>(bytes.size()) * keep)));
      test::StderrCapture capture;
      const std::string result = outcome(path);
      EXPECT_EQ(capture.finish(), "");
      EXPECT_EQ(result.rfind("IoError: " + path.string() + ": ", 0), 0u) << result;
    }
  }
  // PNG and JPEG say what happened.
  const std::string png = encode(drawing(), ".png");
  write_file_atomically(dir / "half.png", png.substr(0, png.size() / 2));
  EXPECT_NE(outcome(dir / "half.png").find("truncated"), std::string::npos) << outcome(dir / "half.png");
  const std::string jpeg = encode(drawing(), ".jpg");
  write_file_atomically(dir / "half.jpg", jpeg.substr(0, jpeg.size() / 2));
  EXPECT_NE(outcome(dir / "half.jpg").find("truncated"), std::string::npos) << outcome(dir / "half.jpg");
  // A PNG whose pixel data is complete but whose IEND chunk is missing is cut short too.
  write_file_atomically(dir / "no-iend.png", png.substr(0, png.size() - 12));
  EXPECT_NE(outcome(dir / "no-iend.png").find("truncated"), std::string::npos) << outcome(dir / "no-iend.png");
}

// A 0 × 0 PNG used to leak libpng's "Image width is zero in IHDR" lines to stderr.
TEST(ImageDecoding, ZeroSizedPngIsAQuietIoError) {
  const fs::path dir = test::fresh_temp_dir("exemplar-zero");
  std::string png = encode(drawing(), ".png");
  for (int i = 16; i < 24; ++i) png[static_cast<std::size_t>(i)] = 0;  // IHDR width and height
  write_file_atomically(dir / "zero.png", png);
  test::StderrCapture capture;
  const std::string result = outcome(dir / "zero.png");
  EXPECT_EQ(capture.finish(), "");
  EXPECT_EQ(result.rfind("IoError: " + (dir / "zero.png").string() + ": ", 0), 0u) << result;
}

// Used to fail: a tracing drawn on a transparent layer (opaque strokes, transparent background,
// the colour under both black) read as a blank image. Its opacity is the drawing.
TEST(ImageDecoding, AlphaOnlyTracingIsRead) {
  const fs::path dir = test::fresh_temp_dir("exemplar-alpha");
  cv::Mat rgba(drawing().rows, drawing().cols, CV_8UC4, cv::Scalar(0, 0, 0, 0));
  std::vector<cv::Mat> channels(4);
  cv::split(rgba, channels);
  channels[3] = drawing().clone();  // opaque where the strokes are
  cv::merge(channels, rgba);
  cv::imwrite((dir / "layer.png").string(), rgba);
  cv::imwrite((dir / "grey.png").string(), drawing());
  const std::string a = stats_of(dir / "grey.png"), b = stats_of(dir / "layer.png");
  EXPECT_EQ(a.substr(a.find("\"total_area\"")), b.substr(b.find("\"total_area\"")));
  // An opaque RGBA image is read by its colour, as before.
  cv::Mat opaque;
  cv::cvtColor(drawing(), opaque, cv::COLOR_GRAY2BGRA);
  cv::imwrite((dir / "opaque.png").string(), opaque);
  const std::string c = stats_of(dir / "opaque.png");
  EXPECT_EQ(a.substr(a.find("\"total_area\"")), c.substr(c.find("\"total_area\"")));
}

// write_grey_png (a simulation's pattern drawing): OpenCV's decoder, independent of ours, and
// load_grey_image read back every pixel; an inconsistent or empty image is refused, and a failed
// write leaves no file.
TEST(ImageDecoding, GreyPngWrittenIsReadBackExactly) {
  const fs::path dir = test::fresh_temp_dir("exemplar-grey-png");
  GreyImage image = test::to_grey_image(test::closed_grid_drawing(203, 4, 40, 3));  // odd width: no row padding hides
  for (std::size_t i = 0; i < image.pixels.size(); i += 7) image.pixels[i] = static_cast<std::uint8_t>(i % 251);
  write_grey_png(dir / "grey.png", image);
  const cv::Mat decoded = cv::imread((dir / "grey.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(decoded.type(), CV_8UC1);
  ASSERT_EQ(decoded.cols, image.width);
  ASSERT_EQ(decoded.rows, image.height);
  EXPECT_TRUE(std::equal(image.pixels.begin(), image.pixels.end(), decoded.datastart));
  EXPECT_EQ(load_grey_image(dir / "grey.png", 1 << 20).pixels, image.pixels);
  GreyImage wrong = image;
  wrong.pixels.pop_back();
  EXPECT_THROW(write_grey_png(dir / "wrong.png", wrong), InvalidInput);
  EXPECT_THROW(write_grey_png(dir / "empty.png", GreyImage{}), InvalidInput);
  EXPECT_THROW(write_grey_png(dir / "missing" / "grey.png", image), IoError);
  EXPECT_FALSE(fs::exists(dir / "wrong.png"));
  EXPECT_FALSE(fs::exists(dir / "empty.png"));
}

// Every format and layout decodes to the same pixels as the PNG: grey and colour, palette BMP,
// TIFF (LZW by OpenCV), 16-bit PNG, top-down BMP.
TEST(ImageDecoding, FormatsAgree) {
  const fs::path dir = test::fresh_temp_dir("exemplar-formats");
  const GreyImage reference = [&] {
    cv::imwrite((dir / "ref.png").string(), drawing());
    return load_grey_image(dir / "ref.png", 1'000'000);
  }();
  cv::Mat colour, wide;
  cv::cvtColor(drawing(), colour, cv::COLOR_GRAY2BGR);
  drawing().convertTo(wide, CV_16U, 257.0);
  const std::vector<std::pair<std::string, cv::Mat>> cases = {
      {"grey.bmp", drawing()}, {"colour.bmp", colour}, {"grey.tiff", drawing()}, {"colour.tiff", colour},
      {"colour.png", colour},  {"wide.png", wide},     {"wide.tiff", wide}};
  for (const auto& [file, image] : cases) {
    SCOPED_TRACE(file);
    ASSERT_TRUE(cv::imwrite((dir / file).string(), image));
    const GreyImage decoded = load_grey_image(dir / file, 1'000'000);
    EXPECT_EQ(decoded.width, reference.width);
    EXPECT_EQ(decoded.height, reference.height);
    EXPECT_EQ(decoded.pixels, reference.pixels);
  }
  // A top-down 8-bit BMP: negate the height and reverse the rows.
  std::string bmp = encode(drawing(), ".bmp");
  const std::uint32_t offset = static_cast<unsigned char>(bmp[10]) | static_cast<unsigned char>(bmp[11]) << 8;
  const int h = drawing().rows, stride = (drawing().cols + 3) / 4 * 4;
  std::string flipped = bmp.substr(0, offset);
  for (int row = h - 1; row >= 0; --row) flipped += bmp.substr(offset + static_cast<std::size_t>(row) * stride, stride);
  const std::int32_t negative = -h;
  std::memcpy(flipped.data() + 22, &negative, 4);
  write_file_atomically(dir / "top-down.bmp", flipped);
  EXPECT_EQ(load_grey_image(dir / "top-down.bmp", 1'000'000).pixels, reference.pixels);
}

// Fuzz: thousands of corrupted PNG, JPEG, TIFF and BMP files made from a small drawing by
// seeded byte flips, overwritten runs, insertions and truncations. Each must decode or be
// refused as an IoError naming the file (InvalidInput only for a header above the pixel limit),
// never crash or hang, and never print to stderr. The 1-megapixel limit bounds every allocation.
TEST(ImageDecoding, FuzzCorruptedFiles) {
  const fs::path dir = test::fresh_temp_dir("exemplar-fuzz");
  const cv::Mat small = test::grid_drawing(48, 16, 2);
  cv::Mat colour;
  cv::cvtColor(small, colour, cv::COLOR_GRAY2BGR);
  const std::vector<std::pair<std::string, std::string>> seeds = {
      {".png", encode(small, ".png")}, {".png", encode(colour, ".png")}, {".jpg", encode(small, ".jpg")},
      {".jpg", encode(colour, ".jpg", {cv::IMWRITE_JPEG_PROGRESSIVE, 1})}, {".tiff", encode(small, ".tiff")},
      {".tiff", encode(colour, ".tiff")}, {".bmp", encode(small, ".bmp")}, {".bmp", encode(colour, ".bmp")}};
  constexpr int kCasesPerSeed = 400;
  int decoded = 0, refused = 0;
  const auto start = std::chrono::steady_clock::now();
  test::StderrCapture capture;
  for (std::size_t s = 0; s < seeds.size(); ++s) {
    const auto& [extension, original] = seeds[s];
    const fs::path path = dir / ("case" + std::to_string(s) + extension);
    for (int c = 0; c < kCasesPerSeed; ++c) {
      Rng rng = Rng::derive(8, "image fuzz", s * kCasesPerSeed + static_cast<std::size_t>(c));
      std::string bytes = original;
      const int edits = 1 + static_cast<int>(rng.uniform_index(4));
      for (int e = 0; e < edits; ++e) {
        // Headers hold the sizes and offsets: half of the edits land in the first 64 bytes.
        const std::size_t span = rng.uniform() < 0.5 ? std::min<std::size_t>(64, bytes.size()) : bytes.size();
        const std::size_t at = rng.uniform_index(span);
        switch (rng.uniform_index(4)) {
          case 0: bytes[at] = static_cast<char>(bytes[at] ^ (1 << rng.uniform_index(8))); break;
          case 1:
            for (std::size_t k = at; k < std::min(bytes.size(), at + 1 + rng.uniform_index(8)); ++k)
              bytes[k] = static_cast<char>(rng.uniform_index(256));
            break;
          case 2: bytes.insert(at, std::string(1 + rng.uniform_index(16), static_cast<char>(rng.uniform_index(256)))); break;
          default: bytes.resize(std::max<std::size_t>(1, at)); break;
        }
      }
      std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      try {
        const GreyImage image = load_grey_image(path, 1'000'000);
        ASSERT_EQ(image.pixels.size(), static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
        ++decoded;
      } catch (const IoError& e) {
        ASSERT_EQ(std::string(e.what()).rfind(path.string() + ": ", 0), 0u) << e.what();
        ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        ++refused;
      } catch (const InvalidInput& e) {
        ASSERT_NE(std::string(e.what()).find(path.string() + ": image is "), std::string::npos) << e.what();
        ASSERT_NE(std::string(e.what()).find("above the limit"), std::string::npos) << e.what();
        ++refused;
      }
    }
  }
  const std::string printed = capture.finish();
  EXPECT_EQ(printed, "") << "library text on stderr";
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("fuzz: %d decoded, %d refused, %.2f s\n", decoded, refused, seconds);
  // Both outcomes occur (a fuzzer that refuses everything, or nothing, tests little).
  EXPECT_GT(decoded, 100);
  EXPECT_GT(refused, 100);
}

}  // namespace
}  // namespace fissure
