#include "fissure/base/error.hpp"

namespace fissure {

void throw_if_problems(std::string_view context, const std::vector<std::string>& problems) {
  if (problems.empty()) return;
  std::string message(context);
  message += ": ";
  for (std::size_t i = 0; i < problems.size(); ++i) message += (i ? "; " : "") + problems[i];
  throw InvalidInput(message);
}

}  // namespace fissure
