#pragma once
/// The baseline a fit has to beat: the Voronoi fracture every mainstream tool makes (Blender's
/// Cell Fracture, Houdini's Voronoi Fracture, Unreal's Chaos and NVIDIA Blast all cut a body into
/// the Voronoi cells of scattered points). On a thin tile the visible face shows the cells of the
/// points that lie near it, so the baseline is the 2-D Voronoi diagram of `cells` uniform points
/// on the W × H face: every cell is one visible fragment, so its fragment count is the exemplar's
/// exactly when `cells` is. It is drawn as render_pattern_image draws a simulated pattern (black
/// lines of the same width on white, the face filling the image), so the exemplar's analysis
/// measures it the way it measures a traced photograph.
#include "fissure/exemplar/crack_image.hpp"
#include "fissure/fracture/pattern_image.hpp"

#include <cstdint>

namespace fissure {

/// The drawing of the Voronoi diagram of `cells` points drawn uniformly on [0, width] × [0, height]
/// from the stream (seed, "voronoi-baseline"). A pixel is a crack when its centre lies within half
/// the line width of its cell's boundary (of a bisector with another point; the face's border is
/// no crack). Throws InvalidInput for non-positive or non-finite sides, cells outside [1, 10⁶] or
/// invalid options. O(pixels · cells).
GreyImage draw_voronoi_baseline(double width, double height, int cells, std::uint64_t seed,
                                const PatternImageOptions& options = {});

}  // namespace fissure
