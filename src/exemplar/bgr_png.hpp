#pragma once
// Writes an OpenCV BGR picture as an RGB PNG with libpng (the exemplar module needs no OpenCV
// codec library: docs/architecture.md), atomically.
#include <opencv2/core.hpp>

#include <filesystem>

namespace fissure::detail {

void write_bgr_png(const std::filesystem::path& path, const cv::Mat& bgr);

}  // namespace fissure::detail
