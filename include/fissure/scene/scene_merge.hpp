#pragma once
/// Joining the slices of a sliced scene fracture (`fissure scene fracture --bodies K/N`, then
/// `fissure scene merge`) into exactly the scene an unsliced run exports, so a street of
/// thousands of slabs can run on any job array.
///
/// Each slice is the whole scene with its share of the bodies fractured (scene_fracture.hpp);
/// its scene extras name the run and the slice. The merge takes every fractured body, with its
/// fragments, from the slice that fractured it and everything else from slice 1. It refuses, naming the
/// file, a scene that is not a slice, slices of different runs (another scene, assignments,
/// seed, age, up or tet count), a slice given twice or missing, and slices whose node lists differ.

#include "fissure/io/scene_export.hpp"

#include <string>
#include <vector>

namespace fissure {

/// The scene extras of slice `k` of `n` of the run `run`: {"fissure": {"slice": [k, n], "run": run}}.
std::string scene_slice_extras(const std::string& run, int k, int n);

/// The merged scene; `names[i]` names `slices[i]` (its file) in messages. Throws InvalidInput.
ExportScene merge_scene_slices(const std::vector<ExportScene>& slices, const std::vector<std::string>& names);

}  // namespace fissure
