#pragma once
/// The fragments of a fractured body as a scene of parts for write_scene()
/// (include/fissure/io/scene_export.hpp): what `fissure fracture -o` writes and the studio exports.
///
/// - One part per fragment, named fragment_NNN (zero-padded to at least three digits, in the
///   fragments' order), its origin at the fragment's centre of mass as Blender's exporter places
///   it, its vertices relative to that origin.
/// - Materials: on the outer faces the input surface's (`appearance`: each outer triangle takes
///   the material of the input triangle nearest to it, AppearanceTransfer), or one named
///   `surface` when the input names none; then `crack` on crack faces (`crack.001`, … if the
///   input has a material of that name).
/// - UVs: outer faces keep the input's, transferred from the nearest input triangle; without
///   input UVs they are box-projected on the axis plane their normal is nearest to, in metres
///   (1 UV unit = 1 m, so one texture tiles the same on every fragment). Crack faces are
///   projected on their crack's plane (the plane of the crack's opening direction), in metres.
///   A vertex where charts meet is written once per chart: glTF and OBJ readers that weld by
///   position (Blender's "merge vertices") get back the closed surface.
/// - Extras per part: fragment index, volume (m³), mass (kg), centre of mass (m), crack-onset
///   time (age units, −1 when no crack bounds it), and contacts (the fragments it touches across
///   cracks with the contact areas, m²).

#include "fissure/fracture/crack_surface.hpp"
#include "fissure/fracture/fragment_mesh.hpp"
#include "fissure/io/scene_export.hpp"
#include "fissure/mesh/surface_mesh.hpp"

#include <string>
#include <vector>

namespace fissure {

/// "fragment_007": the part name of fragment `index` among `count`.
std::string fragment_name(int index, int count);

/// The scene of `fragments`; `cracks` are the ones the fragments' triangle_crack refer to,
/// `density` (kg/m³) gives the masses, and `appearance` (the input surface's, may be empty) the
/// outer faces' materials and UVs.
ExportScene fragment_scene(const std::vector<FragmentMesh>& fragments, const std::vector<CrackSurface>& cracks,
                           double density, const SurfaceAppearance& appearance = {});

}  // namespace fissure
