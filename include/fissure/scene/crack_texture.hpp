#pragma once
/// The cracks of a fractured body drawn in its texture (UV) space: a mask for engines that show
/// cracks as decals over an unbroken mesh, the paper's "converted to textured images in an
/// offline process" (§8). A crack line is where a fragment's outer surface meets a crack face;
/// each such edge is drawn at the UVs the body's surface gives its ends (AppearanceTransfer, as
/// the exported fragments are textured), so the mask lies on the body's own texture.
///
/// Pixel (x, y), row 0 at the top, is UV (x / W, 1 − y / H): the image maps as the body's
/// base-colour texture does with the UVs Fissure reads (v up; glTF's v down is converted on
/// reading and writing). UVs outside [0, 1] (a tiling texture) wrap: each edge is drawn in the
/// unit tile of its midpoint, clipped at the tile's border.

#include "fissure/exemplar/crack_image.hpp"
#include "fissure/fracture/fragment_mesh.hpp"
#include "fissure/mesh/surface_mesh.hpp"

#include <string>
#include <vector>

namespace fissure {

struct CrackTextureOptions {
  int size = 1024;             ///< width and height, pixels
  double line_width_px = 3.0;  ///< the lines' width, antialiased
};

/// 255 on the cracks, 0 elsewhere, antialiased. `fragments` and `appearance` in the same frame
/// (a scene body's world coordinates, FracturedSceneBody). An image of width 0 when the
/// appearance has no UVs (nothing to draw into). Throws InvalidInput for a size outside
/// [16, 16384] or a line width outside (0, 64].
GreyImage crack_texture(const std::vector<FragmentMesh>& fragments, const SurfaceAppearance& appearance,
                        const CrackTextureOptions& options = {});

/// The file a body's crack texture is written to in a folder: its node path without the leading
/// '/', each character other than a letter, digit, '.', '-' or '_' as '_', then ".png"
/// ("/street/sidewalk/slab_01" → "street_sidewalk_slab_01.png").
std::string crack_texture_file_name(const std::string& body_path);

}  // namespace fissure
