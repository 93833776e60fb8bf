#pragma once
// Private to io: a bounds-checked cursor over the bytes of a whole file, shared by the strict
// surface readers (OBJ, PLY, STL, OFF).
//
// Every read checks the bytes that remain, and every count read from a file is checked against
// them before anything is allocated (`check_count`), so a truncated file or a header that claims
// 2·10⁹ vertices in 79 bytes is refused in O(1) instead of being trusted. Errors are IoError
// "<file>:<line>: <what>" while the cursor is in text, "<file>: <what> (byte N)" in binary data.

#include "fissure/base/error.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace fissure::io_detail {

class ByteCursor {
public:
  ByteCursor(std::string_view bytes, std::string name) : m_bytes(bytes), m_name(std::move(name)) {}

  const std::string& name() const { return m_name; }
  std::size_t position() const { return m_pos; }
  std::size_t remaining() const { return m_bytes.size() - m_pos; }
  bool at_end() const { return m_pos >= m_bytes.size(); }
  std::string_view bytes() const { return m_bytes; }

  /// From here on positions are reported as byte offsets (binary data has no lines).
  void enter_binary() { m_binary_from = m_pos; }

  /// "<file>:<line>: " in text, "<file>: " in binary data (the byte offset then goes last).
  std::string where() const;
  [[noreturn]] void fail(const std::string& what) const;

  // --- Text ---
  /// Skips spaces, tabs and carriage returns, not newlines.
  void skip_blanks();
  /// Skips all whitespace, newlines included.
  void skip_whitespace();
  /// The rest of the current line (without its "\r\n" or "\n"); moves past the newline.
  std::string_view line();
  /// The next whitespace-separated word, or an empty view at the end of the file.
  std::string_view word();
  /// The next word on the current line, or an empty view at its end (the newline is not passed).
  std::string_view line_word();
  /// Moves past the next newline (or to the end of the file).
  void next_line();
  /// The next word as a number; fails naming `what` when it is missing or not a number.
  /// Non-finite values ("nan", "inf", 1e999) are returned as NaN or ±inf for the caller to name.
  double number(const char* what);
  std::int64_t integer(const char* what);

  // --- Binary ---
  /// Reads a T stored little- or big-endian; fails when fewer than sizeof(T) bytes remain.
  template <class T>
  T binary(bool big_endian) {
    if (remaining() < sizeof(T)) fail("truncated: the file ends inside its binary data");
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, m_bytes.data() + m_pos, sizeof(T));
    if (big_endian != (std::endian::native == std::endian::big)) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    }
    m_pos += sizeof(T);
    T value;
    std::memcpy(&value, raw, sizeof(T));
    return value;
  }
  /// Moves to byte `offset` (≤ the file's size), e.g. back to re-read a header word.
  void seek(std::size_t offset) { m_pos = std::min(offset, m_bytes.size()); }
  void skip(std::size_t n) {
    if (remaining() < n) fail("truncated: the file ends inside its binary data");
    m_pos += n;
  }

  /// True when `count` items of at least `min_bytes_each` bytes fit in the bytes that remain
  /// (`slack` allows for a text file's missing last newline). Overflow-safe.
  bool fits(std::uint64_t count, std::uint64_t min_bytes_each, std::uint64_t slack = 0) const {
    return min_bytes_each == 0 || count <= (remaining() + slack) / min_bytes_each;
  }
  /// Fails with "truncated or corrupt: <what> count N needs at least N·b bytes, only K are left"
  /// unless fits(count, min_bytes_each, slack).
  void check_count(std::uint64_t count, std::uint64_t min_bytes_each, const char* what, std::uint64_t slack = 0) const;

private:
  std::string_view m_bytes;
  std::string m_name;
  std::size_t m_pos = 0;
  std::size_t m_binary_from = std::string_view::npos;
};

/// Parses all of `text` as a number (std::from_chars: locale-free, no leading '+'), true on
/// success; an out-of-range value such as 1e999 comes back as ±inf.
bool parse_double(std::string_view text, double& value);
/// Parses all of `text` as a decimal integer, true on success and when it fits.
bool parse_integer(std::string_view text, std::int64_t& value);

/// Lower-case copy of an ASCII word, for keywords that files write in either case.
std::string lower_ascii(std::string_view text);

}  // namespace fissure::io_detail
