#pragma once
/// nlohmann::json's exception text as one line for a user, shared by every JSON reader (base
/// does not link the JSON library: this works on the text of e.what()).

#include <string>
#include <string_view>

namespace fissure {

/// "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error while parsing
/// value - invalid literal; last read: 'x'" → "syntax error at line 3, column 5: invalid
/// literal; last read: 'x'". Other exceptions (an out_of_range for 1e999) keep their text
/// without the "[json.exception…]" tag. Newlines become spaces (nlohmann escapes control
/// characters in "last read", but a message is one line whatever comes).
std::string json_error_text(std::string_view what);

}  // namespace fissure
