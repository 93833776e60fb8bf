#include "fissure/base/number_text.hpp"

#include "fissure/base/error.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace fissure {

std::string format_number(double value, int significant_digits) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (value == 0.0) return "0";  // not "-0" (a negated zero force component in a load spec)
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", significant_digits < 1 ? 1 : significant_digits, value);
  return buffer;
}

std::vector<double> parse_number_list(std::string_view text, std::string_view context) {
  std::vector<double> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    std::string_view item = text.substr(pos, comma - pos);
    while (!item.empty() && (item.front() == ' ' || item.front() == '\t')) item.remove_prefix(1);
    while (!item.empty() && (item.back() == ' ' || item.back() == '\t')) item.remove_suffix(1);
    double value = 0.0;
    // from_chars rejects a leading '+', which users type ("+1e4"); accept it.
    std::string_view digits = item;
    if (digits.size() > 1 && digits.front() == '+' && digits[1] != '-') digits.remove_prefix(1);
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (item.empty() || ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value)) {
      throw InvalidInput(std::string(context) + ": '" + std::string(item) + "' is not a finite number");
    }
    out.push_back(value);
    pos = comma + 1;
  }
  return out;
}

std::vector<double> parse_number_list(std::string_view text, std::string_view context, std::size_t count,
                                      std::string_view names) {
  // Count first: "1,1" for three weights is a missing number, not a malformed one.
  std::size_t items = 1;
  for (char c : text) items += c == ',';
  if (items != count) {
    throw InvalidInput(std::string(context) + ": expected " + std::to_string(count) + " numbers " +
                       std::string(names) + ", got " + std::to_string(text.empty() ? 0 : items));
  }
  return parse_number_list(text, context);
}

}  // namespace fissure
