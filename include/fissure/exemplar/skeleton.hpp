#pragma once
/// Thinning of a binary crack mask to a one-pixel-wide, 8-connected skeleton.

#include <cstdint>
#include <vector>

namespace fissure {

/// Zhang–Suen thinning (CACM 27(3), 1984; the method of scikit-image's skeletonize, which the
/// shared reference statistics use), with the two sub-iterations' deletion rules in lookup
/// tables over the 256 neighbourhood codes, and only pixels next to a deletion re-examined:
/// O(crack pixels × line width). `mask` is row-major width × height, non-zero = set; pixels on
/// the image frame are treated as having background outside. Returns 1 for skeleton pixels.
std::vector<std::uint8_t> thin_to_skeleton(const std::vector<std::uint8_t>& mask, int width, int height);

}  // namespace fissure
