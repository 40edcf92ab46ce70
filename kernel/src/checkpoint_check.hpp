// Field-by-field checks of a checkpoint just read into the world, run before
// any stage or index uses it: every index in range of this scene, every
// count matching it, every value finite and where it can be. A checksum
// catches damage; these catch a file that is intact but wrong.
#pragma once

#include <string>

namespace talus {

class World;
struct RunState;

// Throws InputError "error: checkpoint PATH: <what is wrong>".
void check_restored_state(const std::string& path, const World& world, const RunState& state);

}  // namespace talus
