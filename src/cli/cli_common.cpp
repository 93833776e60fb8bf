#include "cli_common.hpp"

#include "option_checks.hpp"

#include "fissure/base/thread_count.hpp"

#include <cmath>

namespace fissure::cli {

void add_threads_option(CLI::App& cmd) {
  // count_in: "abc" is "not a number", not "not in range 1 to 1024" as CLI::Range put it.
  cmd.add_option_function<double>("--threads", [](double n) { set_thread_count(static_cast<int>(std::lround(n))); },
                                  "Threads for all work (default $FISSURE_THREADS, else every hardware thread); "
                                  "results are identical at any count")
      ->type_name("N")->check(count_in(1, 1024));
}

std::FILE* summary_stream(const std::string& output) { return output == "-" ? stderr : stdout; }

}  // namespace fissure::cli
