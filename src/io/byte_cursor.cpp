#include "byte_cursor.hpp"

#include <algorithm>
#include <charconv>
#include <limits>

namespace fissure::io_detail {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
bool is_space(char c) { return is_blank(c) || c == '\n'; }

// from_chars refuses a leading '+', which some exporters write.
std::string_view without_plus(std::string_view text) {
  return text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+' ? text.substr(1) : text;
}

}  // namespace

bool parse_double(std::string_view text, double& value) {
  text = without_plus(text);
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (end != text.data() + text.size()) return false;
  if (ec == std::errc::result_out_of_range) {
    // Too large (1e999, 400 digits) or too small (1e-999) for a double: ±inf or ±0, decided by
    // the exponent's sign, or without one by whether the integer part has a non-zero digit.
    const bool negative = text[0] == '-';
    const std::size_t e = text.find_first_of("eE");
    bool large;
    if (e != std::string_view::npos) {
      large = e + 1 < text.size() && text[e + 1] != '-';
    } else {
      const std::string_view integer_part = text.substr(0, text.find('.'));
      large = integer_part.find_first_of("123456789") != std::string_view::npos;
    }
    value = large ? std::numeric_limits<double>::infinity() : 0.0;
    if (negative) value = -value;
    return true;
  }
  return ec == std::errc();
}

bool parse_integer(std::string_view text, std::int64_t& value) {
  text = without_plus(text);
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

std::string lower_ascii(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

std::string ByteCursor::where() const {
  if (m_pos >= m_binary_from) return m_name + ": ";
  const std::size_t end = std::min(m_pos, m_bytes.size());
  const auto line = 1 + std::count(m_bytes.begin(), m_bytes.begin() + static_cast<std::ptrdiff_t>(end), '\n');
  return m_name + ":" + std::to_string(line) + ": ";
}

void ByteCursor::fail(const std::string& what) const {
  if (m_pos >= m_binary_from) throw IoError(where() + what + " (byte " + std::to_string(m_pos) + ")");
  throw IoError(where() + what);
}

void ByteCursor::skip_blanks() {
  while (m_pos < m_bytes.size() && is_blank(m_bytes[m_pos])) ++m_pos;
}

void ByteCursor::skip_whitespace() {
  while (m_pos < m_bytes.size() && is_space(m_bytes[m_pos])) ++m_pos;
}

std::string_view ByteCursor::line() {
  const std::size_t start = m_pos;
  const std::size_t newline = m_bytes.find('\n', m_pos);
  const std::size_t end = newline == std::string_view::npos ? m_bytes.size() : newline;
  m_pos = newline == std::string_view::npos ? m_bytes.size() : newline + 1;
  std::string_view text = m_bytes.substr(start, end - start);
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  return text;
}

std::string_view ByteCursor::word() {
  skip_whitespace();
  const std::size_t start = m_pos;
  while (m_pos < m_bytes.size() && !is_space(m_bytes[m_pos])) ++m_pos;
  return m_bytes.substr(start, m_pos - start);
}

std::string_view ByteCursor::line_word() {
  skip_blanks();
  const std::size_t start = m_pos;
  while (m_pos < m_bytes.size() && !is_space(m_bytes[m_pos])) ++m_pos;
  return m_bytes.substr(start, m_pos - start);
}

void ByteCursor::next_line() {
  const std::size_t newline = m_bytes.find('\n', m_pos);
  m_pos = newline == std::string_view::npos ? m_bytes.size() : newline + 1;
}

double ByteCursor::number(const char* what) {
  const std::string_view w = word();
  if (w.empty()) fail(std::string("truncated: the file ends where ") + what + " should be");
  double value;
  if (!parse_double(w, value)) fail("'" + std::string(w.substr(0, 40)) + "' is not a number (" + what + ")");
  return value;
}

std::int64_t ByteCursor::integer(const char* what) {
  const std::string_view w = word();
  if (w.empty()) fail(std::string("truncated: the file ends where ") + what + " should be");
  std::int64_t value;
  if (!parse_integer(w, value)) fail("'" + std::string(w.substr(0, 40)) + "' is not an integer (" + what + ")");
  return value;
}

void ByteCursor::check_count(std::uint64_t count, std::uint64_t min_bytes_each, const char* what, std::uint64_t slack) const {
  if (fits(count, min_bytes_each, slack)) return;
  fail("truncated or corrupt: " + std::string(what) + " count " + std::to_string(count) + " needs at least " +
       std::to_string(min_bytes_each) + " bytes each, but only " + std::to_string(remaining()) + " bytes are left");
}

}  // namespace fissure::io_detail
