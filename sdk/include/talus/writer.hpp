// Output writers get read-only views of the world on their own schedule.
// They must write to a temporary name and rename, so that a failure never
// leaves a truncated file that looks good, and throw RunError naming the path
// and the system's reason on failure.
#pragma once

#include <string>
#include <vector>

#include "talus/plugin.hpp"

namespace talus {

class World;

struct OutputContext {
  std::string directory;      // existing, writable output folder
  std::string scene_name;     // scene file stem, used as the file prefix
  std::string scene_text;     // the scene file's text, for metadata
  std::string talus_version;
  // True when the run continues from a checkpoint: keep what was written up
  // to world.time and append after it instead of starting new files.
  bool resume = false;
};

class TALUS_API Writer : public Model {
 public:
  ~Writer() override;

  virtual void open(const OutputContext& context, const World& world) = 0;
  virtual void write(const World& world) = 0;  // one frame at world.time
  virtual void close(const World& /*world*/) {}
  // Files written so far, for the run summary.
  virtual std::vector<std::string> files() const = 0;
};

}  // namespace talus
