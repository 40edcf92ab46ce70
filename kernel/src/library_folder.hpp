// The folder libtalus was loaded from: where the built-in plugins and the
// MPI side of the runtime are found, in a build tree and an installed one.
#pragma once

#include <filesystem>

namespace talus {

// Empty if the dynamic loader cannot say (dladdr failed).
std::filesystem::path library_folder();

}  // namespace talus
