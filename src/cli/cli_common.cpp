#include "cli_common.hpp"

namespace fissure::cli {

std::FILE* summary_stream(const std::string& output) { return output == "-" ? stderr : stdout; }

}  // namespace fissure::cli
