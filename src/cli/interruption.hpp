#pragma once
// Ctrl-C (SIGINT) and SIGTERM for the CLI. The first signal sets a CancelToken that the core
// checks (tetrahedralize, modal analysis); the command then ends with "fissure: cancelled", exit
// 6, and writes nothing. A second signal kills at once (the default action).
//
// The core reads the token inside tetrahedralize (CGAL's refinement and sliver removal, tens
// of ms), the modal solve and the fracture simulation, but not everywhere: image analysis
// (analyze, compare), the static solve's factorisation, reading and repairing a surface, and
// the O(tets) steps between tetrahedralize's checks (at 2M tets, seconds) do not. So while no
// output is being written (an AbandonableWork is alive), a signal that the core has not
// answered within kGraceSeconds ends the process directly: nothing is lost, because every
// output is written after the computation, through a temporary file.

#include "fissure/base/progress.hpp"

namespace fissure::cli {

/// Installs the handlers (once, from main). A signal the parent ignored (a background job of a
/// non-interactive shell ignores SIGINT) stays ignored.
void install_interrupt_handlers();

/// The token every long core call gets.
const CancelToken& interrupt_token();

/// Throws Cancelled when a signal came: commands call it between their stages and before
/// writing, so an interrupted run never writes a result.
void throw_if_interrupted();

/// Seconds the core gets to stop by itself after a signal before the process is ended.
inline constexpr unsigned kGraceSeconds = 2;

/// Marks a stretch during which no output file is open (reading, computing), so an unanswered
/// signal may end the process. Not nestable; the write of the results comes after it.
class AbandonableWork {
public:
  AbandonableWork();
  ~AbandonableWork();
  AbandonableWork(const AbandonableWork&) = delete;
  AbandonableWork& operator=(const AbandonableWork&) = delete;
};

}  // namespace fissure::cli
