#include "talus/params.hpp"
#include "text.hpp"

namespace talus {

void Diagnostics::error(const ParamValues& where, std::string_view name, std::string message, std::string hint) {
  error(where.file(), name.empty() ? where.pointer() : where.pointer(name), std::move(message), std::move(hint));
}

void Diagnostics::error(std::string file, std::string pointer, std::string message, std::string hint) {
  items_.push_back({std::move(file), pointer.empty() ? "/" : std::move(pointer), std::move(message), std::move(hint)});
}

std::string Diagnostics::format() const {
  std::string out;
  for (const auto& d : items_) {
    out += "error: " + d.file + ": " + d.pointer + ": " + d.message + "\n";
    if (!d.hint.empty()) out += "       " + d.hint + "\n";
  }
  return out;
}

}  // namespace talus
