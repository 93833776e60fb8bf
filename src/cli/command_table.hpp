#pragma once
// The commands of `fissure`: one table that the dispatcher (main.cpp) lists in its help and
// dispatches on, and that each command's executable takes its summary from, so the two cannot
// drift. Each command but `version` is its own executable, fissure-<name>, in libexec/fissure/
// beside bin/: a command loads only the libraries it uses (docs/architecture.md, "Start-up").

#include <array>
#include <stdexcept>
#include <string_view>

namespace fissure::cli {

struct CommandInfo {
  std::string_view name;
  std::string_view summary;
};

inline constexpr std::array<CommandInfo, 9> kCommands{{
    {"mesh", "Tetrahedralise a closed surface (or a procedural tile) into a gmsh .msh file"},
    {"solve", "Static stress of a tet mesh under loads: writes displacement, stress and max principal stress as "
              "gmsh views"},
    {"modes", "Lowest natural frequencies of a tet mesh, printed as JSON (Hz)"},
    {"analyze", "Crack statistics of a traced crack image (paper S1-S3): fragments, cracks, junctions and junction "
                "angles"},
    {"compare", "Statistical distance between two crack patterns (paper Eq. 5)"},
    {"fracture", "Fracture a body (paper S5): cracks over time, fragment labels, and the visible pattern measured "
                 "like an exemplar"},
    {"fit", "Fit a fracture material to a traced crack image by ABC (paper S6): the paper's best-of-N or ABC-SMC"},
    {"scene", "Scenes of many bodies (issue 13): list a scene's bodies, materials and which can be fractured"},
    {"version", "Print the Fissure version"},
}};

/// The entry of `name`; the table is the only place names are defined, so a miss is a bug.
constexpr const CommandInfo& command_info(std::string_view name) {
  for (const CommandInfo& info : kCommands)
    if (info.name == name) return info;
  throw std::logic_error("fissure: command missing from kCommands");
}

}  // namespace fissure::cli
