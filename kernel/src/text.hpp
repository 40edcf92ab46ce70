// Small text helpers shared by the validator, the CLI and the messages.
#pragma once

#include "talus/config.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace talus::text {

// Levenshtein distance, for "did you mean".
TALUS_API std::size_t edit_distance(std::string_view a, std::string_view b);
// The closest candidate within a small distance, or empty.
TALUS_API std::string closest(std::string_view word, const std::vector<std::string>& candidates);
TALUS_API std::string join(const std::vector<std::string>& items, std::string_view separator = ", ");
// Shortest round-trip representation of a number, as a user wrote it.
TALUS_API std::string number(double v);
// JSON-pointer escaping of one reference token (~ -> ~0, / -> ~1).
TALUS_API std::string pointer_token(std::string_view key);
// The whole of a file, bytes as they are; false (errno set) if it cannot be opened.
TALUS_API bool read_file(const std::string& path, std::string& text);

}  // namespace talus::text
