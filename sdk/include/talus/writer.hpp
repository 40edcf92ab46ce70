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

// One named result of a whole run (an analysis' wave height, its breaker type).
struct WriterResult {
  std::string name;
  double number = 0.0;
  std::string text;  // a textual result when not empty (then `number` is unused)
};

class TALUS_API Writer : public Model {
 public:
  ~Writer() override;

  // Checks the parameters against the set-up world (fields that exist, points
  // inside the domain) and throws InputError naming the JSON pointer. The
  // host calls it while it builds the run, so `talus validate` refuses what
  // open() would and nothing is written for a scene that cannot run.
  virtual void check(const World& /*world*/) const {}
  // Called once check() passed, in the existing output folder.
  virtual void open(const OutputContext& context, const World& world) = 0;
  virtual void write(const World& world) = 0;  // one frame at world.time
  virtual void close(const World& /*world*/) {}
  // Files written so far, for the run summary.
  virtual std::vector<std::string> files() const = 0;
  // The columns of the time series this writer records for this world (a CSV
  // header), known once check() passes: `talus study` refuses a measure that
  // names none of them before anything runs. Writers of fields return none.
  virtual std::vector<std::string> series(const World& /*world*/) const { return {}; }
  // Results of the whole run, known once close() ran: the run summary lists
  // them under "results" / TYPE / NAME, where `talus study` measures name
  // them; result_names() says before the run which there will be.
  virtual std::vector<std::string> result_names() const { return {}; }
  virtual std::vector<WriterResult> results() const { return {}; }
  // On several MPI ranks: true when open(), write() and close() run on every
  // rank, each taking its owned rows (ParticleStore::owned_size()): written
  // into the one file the ranks share, or summed and the sums added over the
  // ranks (Parallel::sum) for rank 0 to write. The halo copies are refreshed
  // from their owners before. Otherwise the host calls them on rank 0 alone,
  // which then holds a copy of every particle.
  virtual bool writes_on_every_rank() const { return false; }
};

}  // namespace talus
