#include "option_checks.hpp"

#include "fissure/base/error.hpp"
#include "fissure/base/number_text.hpp"

#include <cctype>
#include <charconv>
#include <filesystem>
#include <cmath>
#include <cstdint>

namespace fissure::cli {
namespace {

// The value as from_chars reads it; false for anything that is not entirely one number. A
// leading '+' is allowed, as users type it.
bool read_number(std::string_view text, double& value) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && ec == std::errc() && end == text.data() + text.size();
}

std::string range_text(double lo, double hi) { return "[" + format_number(lo) + ", " + format_number(hi) + "]"; }

}  // namespace

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        if (!read_number(text, value) || !std::isfinite(value)) return "'" + text + "' is not a finite number";
        return {};
      },
      "FINITE");
}

CLI::Validator parameter_range(const ParameterInfo& info) {
  const std::string range = parameter_range_text(info);
  return CLI::Validator(
      [info, range](std::string& text) -> std::string {
        double value = 0.0;
        if (!read_number(text, value) || !std::isfinite(value)) return "'" + text + "' is not a finite number";
        if (!parameter_problem(info, value, info.flag).empty()) return text + " is outside " + range;
        return {};
      },
      "in " + range);
}

CLI::Validator finite_in(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double value = 0.0;
        if (!read_number(text, value) || !std::isfinite(value)) return "'" + text + "' is not a finite number";
        if (value < lo || value > hi) return text + " is outside " + range_text(lo, hi);
        return {};
      },
      "FINITE in " + range_text(lo, hi));
}

CLI::Validator count_in(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double value = 0.0;
        if (!read_number(text, value) || !std::isfinite(value) || value != std::floor(value)) {
          return "'" + text + "' is not a whole number";
        }
        if (value < lo || value > hi) return text + " is outside " + range_text(lo, hi);
        return {};
      },
      "a whole number in " + range_text(lo, hi));
}

CLI::Validator seed_value() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::string_view digits = text;
        if (digits.size() > 1 && digits.front() == '+') digits.remove_prefix(1);
        std::uint64_t value = 0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (digits.empty() || end != digits.data() + digits.size() ||
            (ec != std::errc() && ec != std::errc::result_out_of_range))
          return "'" + text + "' is not a whole number from 0 to 18446744073709551615";
        if (ec == std::errc::result_out_of_range) return text + " is larger than 18446744073709551615 (2^64 - 1)";
        return {};
      },
      "SEED in [0, 2^64-1]");
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

CLI::Validator png_path() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::string ext = lower_extension(text);
        if (ext.empty() || ext == ".png") return {};
        return text + ": the image is written as PNG; name it .png";
      },
      "PNG");
}

}  // namespace fissure::cli
