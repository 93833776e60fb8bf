#pragma once
// Private to io: triangulation of one polygonal face of an OBJ, PLY or OFF file.
//
// Convex faces (nearly all quads and n-gons written by modellers) are split as a fan from their
// first vertex; non-convex ones are ear-clipped in the plane of their Newell normal, so an L- or
// U-shaped cap stays inside its outline as it did with assimp's aiProcess_Triangulate.

#include <cstddef>
#include <span>
#include <vector>

namespace fissure::io_detail {

/// Largest non-convex face that is ear-clipped: clipping costs O(n²) per face, so a corrupt file
/// of huge concave faces could otherwise take hours. Modellers' n-gons are far smaller.
inline constexpr std::size_t kMaxConcaveFaceVertices = 1024;

/// Appends the triangles of `polygon` (indices into `xyz`, 3 doubles per vertex, ≥ 3 of them) to
/// `triangles`, 3 indices each, with the polygon's orientation. Returns false, adding nothing,
/// when the face is non-convex and has more than kMaxConcaveFaceVertices vertices. A degenerate
/// face (zero area, repeated vertices) is fanned; repair_surface later drops its slivers.
bool triangulate_polygon(const std::vector<double>& xyz, std::span<const int> polygon, std::vector<int>& triangles);

}  // namespace fissure::io_detail
