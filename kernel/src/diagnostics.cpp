#include "talus/params.hpp"

#include <cstdio>

#include "text.hpp"

namespace talus {

void Diagnostics::error(const ParamValues& where, std::string_view name, std::string message, std::string hint) {
  error(where.file(), name.empty() ? where.pointer() : where.pointer(name), std::move(message), std::move(hint));
}

void Diagnostics::error(std::string file, std::string pointer, std::string message, std::string hint) {
  items_.push_back({std::move(file), pointer.empty() ? "/" : std::move(pointer), std::move(message), std::move(hint)});
}

namespace {

// Control characters a scene smuggled into a key or value, written as \u00XX:
// a NUL would otherwise end the printed report there. A line break that
// starts an indented line is the message's own layout (a refused plugin's
// reasons, one a line) and is kept: no line it starts can pass for a report
// line of its own.
std::string printable(const std::string& s) {
  std::string out;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const char c = s[k];
    const bool indented_line = c == '\n' && k + 1 < s.size() && s[k + 1] == ' ';
    if ((static_cast<unsigned char>(c) >= 0x20 && c != 0x7f) || indented_line) {
      out += c;
      continue;
    }
    char code[8];
    std::snprintf(code, sizeof code, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
    out += code;
  }
  return out;
}

}  // namespace

std::string Diagnostics::format() const {
  std::string out;
  for (const auto& d : items_) {
    out += "error: " + printable(d.file) + ": " + printable(d.pointer) + ": " + printable(d.message) + "\n";
    if (!d.hint.empty()) out += "       " + printable(d.hint) + "\n";
  }
  return out;
}

}  // namespace talus
