#include "library_folder.hpp"

#include <dlfcn.h>

namespace talus {

std::filesystem::path library_folder() {
  Dl_info info{};
  if (!dladdr(reinterpret_cast<void*>(&library_folder), &info) || !info.dli_fname) return {};
  return std::filesystem::weakly_canonical(info.dli_fname).parent_path();
}

}  // namespace talus
