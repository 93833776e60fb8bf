#include "fissure/base/json_error_text.hpp"

namespace fissure {

std::string json_error_text(std::string_view what) {
  std::string text(what);
  const std::size_t bracket = text.find("] ");
  if (bracket != std::string::npos) text = text.substr(bracket + 2);
  if (text.rfind("parse error ", 0) == 0) text = "syntax error " + text.substr(12);
  const std::size_t detail = text.find(": syntax error while parsing ");
  if (detail != std::string::npos) {
    const std::size_t dash = text.find(" - ", detail);
    if (dash != std::string::npos) text = text.substr(0, detail) + ": " + text.substr(dash + 3);
  }
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace fissure
