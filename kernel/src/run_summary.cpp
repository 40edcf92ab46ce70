// The summary is built from the stages and writers themselves, after the writers
// have closed, so it names every file a run wrote.
#include "run_summary.hpp"

#include <omp.h>
#include <sys/resource.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "talus/number_text.hpp"
#include "progress.hpp"
#include "simulation.hpp"
#include "talus/blocks.hpp"
#include "talus/error.hpp"
#include "talus/stage.hpp"
#include "talus/world.hpp"
#include "talus/writer.hpp"
#include "text.hpp"

namespace talus {

// The high-water mark of this process's own memory (VmHWM). Not getrusage's
// ru_maxrss: Linux folds into it the peak of whatever ran in this process
// before exec (the shell, Python or `talus study` that started it), so a
// small run started from a large process would report the larger peak.
double peak_memory_mib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::strtod(line.c_str() + 6, nullptr) / 1024.0;  // kB
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

std::string fields_in_float(const ParticleStore& store) {
  std::vector<std::string> names;
  for (const FieldInfo& f : store.fields())
    if (is_single(f.type)) names.push_back(f.name);
  return names.empty() ? "none" : text::join(names);
}

const std::vector<std::string>& summary_keys() {
  static const std::vector<std::string> keys = {
      "scene",     "steps",     "time",    "wall_seconds", "fluid_particles", "wall_particles",
      "blocks",    "particle_steps", "wall_particle_steps", "peak_memory_mib", "removed", "wall_crossings",
      "warnings",  "threads",   "finish",  "phases_s",     "stages",          "outputs", "results", "ranks",
      "precision"};
  return keys;
}

void write_summary_file(const RunSummary& r, const std::string& path) {
  const World& world = r.world;
  nlohmann::json summary = {{"scene", r.scene_path},
                            {"steps", r.steps},
                            {"time", world.time},
                            {"wall_seconds", r.wall_seconds},
                            {"fluid_particles", world.fluid.size()},
                            {"wall_particles", world.boundary.size()},
                            {"blocks", world.blocks ? world.blocks->size() : 0},
                            {"particle_steps", r.particle_steps},
                            {"wall_particle_steps", r.wall_particle_steps},
                            {"peak_memory_mib", r.peak_memory_mib},
                            {"removed", world.removed},
                            {"wall_crossings", world.wall_crossings},
                            {"warnings", world.warnings.all()},
                            {"threads", omp_get_max_threads()},
                            {"precision", {{"mode", world.fluid.mixed_precision() ? "mixed" : "double"},
                                           {"fluid_in_float", fields_in_float(world.fluid)},
                                           {"walls_in_float", fields_in_float(world.boundary)}}},
                            {"finish", r.finish_lines},
                            {"ranks", {{"count", r.ranks.count},
                                       {"imbalance", r.ranks.imbalance},
                                       {"halo_share", r.ranks.halo_share},
                                       {"rebuilds", r.ranks.rebuilds},
                                       {"rebalances", r.ranks.rebalances},
                                       {"cost_imbalance", r.ranks.cost_imbalance},
                                       {"cost_imbalance_mean", r.ranks.cost_imbalance_mean},
                                       {"peak_memory_mib_max", r.ranks.peak_memory_mib_max}}}};
  nlohmann::json stage_seconds = nlohmann::json::object();
  for (std::size_t i = 0; i < r.stages.size() && i < r.phases.stages.size(); ++i)
    stage_seconds[r.stage_names[i]] = r.phases.stages[i];
  summary["phases_s"] = {{"setup", r.phases.setup},
                         {"stages", stage_seconds},
                         {"outputs", r.phases.outputs},
                         {"host", r.phases.host}};
  nlohmann::json statuses = nlohmann::json::object();
  for (std::size_t i = 0; i < r.stages.size(); ++i) statuses[r.stage_names[i]] = r.stages[i]->status(world);
  summary["stages"] = statuses;
  nlohmann::json files = nlohmann::json::object();
  for (const auto& w : r.writers) {  // two writers of one type: both lists, in scene order
    nlohmann::json& list = files[w.type];
    if (list.is_null()) list = nlohmann::json::array();
    for (const auto& file : w.writer->files()) list.push_back(file);
  }
  summary["outputs"] = files;
  nlohmann::json results = nlohmann::json::object();
  for (const auto& w : r.writers)
    for (const auto& result : w.writer->results()) {
      nlohmann::json& value = results[w.type][result.name];
      if (!result.text.empty()) value = result.text;
      else if (std::isfinite(result.number)) value = result.number;  // JSON has no NaN: an absent result is null
    }
  summary["results"] = results;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << summary.dump(2) << "\n";
    if (!out) throw RunError("error: cannot write " + tmp + ": " + std::strerror(errno));
  }
  std::filesystem::rename(tmp, path);
}

namespace {

// "time: set-up 1.2 s, wcsph 30.1 s (95 %), outputs 0.8 s, host 0.4 s"
void print_phases(const RunSummary& r) {
  const PhaseTimes& p = r.phases;
  double total = p.setup + p.outputs + p.host;
  for (double s : p.stages) total += s;
  if (!(total > 0.0)) return;
  auto part = [&](const std::string& name, double seconds) {
    return name + " " + fixed(seconds, 3) + " s (" + fixed(100.0 * seconds / total, 2) + " %)";
  };
  std::string line = part("set-up", p.setup);
  for (std::size_t i = 0; i < p.stages.size() && i < r.stage_names.size(); ++i)
    line += ", " + part(r.stage_names[i], p.stages[i]);
  line += ", " + part("outputs", p.outputs) + ", " + part("host", p.host);
  std::printf("       time: %s\n", line.c_str());
}

}  // namespace

void print_summary(const RunSummary& r) {
  const World& world = r.world;
  const std::uint64_t steps = r.steps;
  const double wall = r.wall_seconds;
  std::printf("talus: done: %llu steps to t = %s s in %s wall (%.3g steps/s, %.3g M particle-steps/s), "
              "peak memory %.0f MiB\n",
              static_cast<unsigned long long>(steps), fixed(world.time, 6).c_str(), clock_text(wall).c_str(),
              wall > 0 ? steps / wall : 0.0, wall > 0 ? r.particle_steps / wall / 1e6 : 0.0, r.peak_memory_mib);
  if (r.ranks.count > 1)
    std::printf("       %d MPI ranks: imbalance %.3f (cost %.3f on average, %.3f at worst), halo %.1f %% of the owned "
                "particles, %llu rebuilds, %llu rebalances, peak memory %.0f MiB on the largest rank\n",
                r.ranks.count, r.ranks.imbalance, r.ranks.cost_imbalance_mean, r.ranks.cost_imbalance,
                100.0 * r.ranks.halo_share,
                static_cast<unsigned long long>(r.ranks.rebuilds), static_cast<unsigned long long>(r.ranks.rebalances),
                r.ranks.peak_memory_mib_max);
  if (r.wall_particle_steps > 0 && wall > 0)
    std::printf("       %.3g M particle-steps/s counting the wall particles too (as bench_wcsph and DualSPHysics do)\n",
                static_cast<double>(r.particle_steps + r.wall_particle_steps) / wall / 1e6);
  for (const auto& warning : world.warnings.all()) std::printf("       warning: %s\n", warning.c_str());
  if (world.wall_crossings)
    std::printf("       %llu fluid particles passed into a wall (the warnings say where and when the first did)\n",
                static_cast<unsigned long long>(world.wall_crossings));
  if (world.removed) std::printf("       %llu fluid particles left the domain and were removed\n",
                                 static_cast<unsigned long long>(world.removed));
  print_phases(r);
  for (std::size_t i = 0; i < r.stages.size(); ++i) {
    const std::string st = r.stages[i]->status(world);
    if (!st.empty()) std::printf("       %s: %s\n", r.stage_names[i].c_str(), st.c_str());
  }
  for (const auto& line : r.finish_lines) std::printf("       %s\n", line.c_str());
  for (const auto& w : r.writers) {
    const auto files = w.writer->files();
    if (files.empty()) continue;
    std::printf("       %s: %s%s\n", w.type.c_str(), files.back().c_str(),
                files.size() > 1 ? (" (and " + std::to_string(files.size() - 1) + " more)").c_str() : "");
  }
}

}  // namespace talus
