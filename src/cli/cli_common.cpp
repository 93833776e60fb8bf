#include "cli_common.hpp"

#include "fissure/base/thread_count.hpp"

namespace fissure::cli {

void add_threads_option(CLI::App& cmd) {
  cmd.add_option_function<int>("--threads", [](int n) { set_thread_count(n); },
                               "Threads for all work (default $FISSURE_THREADS, else every hardware thread); "
                               "results are identical at any count")
      ->check(CLI::Range(1, 1024));
}

std::FILE* summary_stream(const std::string& output) { return output == "-" ? stderr : stdout; }

}  // namespace fissure::cli
