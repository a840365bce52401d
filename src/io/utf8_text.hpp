#pragma once
// UTF-8 checks for text that goes into a TOML file: a TOML document must be valid UTF-8 throughout,
// comments included, while paths and command-line words are bytes.
#include <string>
#include <string_view>

namespace granflow {

// Whether `text` is well-formed UTF-8 (no stray continuation bytes, no overlong forms, no surrogates,
// nothing above U+10FFFF).
bool is_valid_utf8(std::string_view text);

// `text` with each byte that is not part of a well-formed UTF-8 sequence written as \xNN, so that a
// path of other bytes can stand in a TOML comment and still be read by eye.
std::string utf8_or_escaped(std::string_view text);

}  // namespace granflow
