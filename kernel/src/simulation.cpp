#include "simulation.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

#include "talus/number_text.hpp"
#include "output_schedule.hpp"
#include "progress.hpp"
#include "ranks.hpp"
#include "run_summary.hpp"
#include "stop_signals.hpp"
#include "talus/blocks.hpp"
#include "talus/build_info.hpp"
#include "talus/error.hpp"
#include "talus/stage.hpp"
#include "talus/writer.hpp"
#include "text.hpp"

namespace fs = std::filesystem;

namespace talus {

Simulation::Simulation(PluginRegistry& registry, Scene scene) : registry_(registry), scene_(std::move(scene)) {
  const ParamValues& s = scene_.values;
  const ParamValues& domain = s.object("domain");
  world_.dim = static_cast<int>(domain.integer("dim"));
  world_.lo = domain.vector("min");
  world_.hi = domain.vector("max");
  for (const auto& axis : domain.strings("periodic")) world_.periodic[axis[0] - 'x'] = true;
  world_.gravity = s.vector("gravity");
  world_.end_time = s.object("time").real("end");
  resort_every_ = static_cast<std::uint64_t>(s.object("time").integer("resort_every"));
  // Before any field exists: the stores choose each field's type as it is required.
  const bool mixed = s.string("precision") == "mixed";
  world_.fluid.set_mixed_precision(mixed);
  world_.boundary.set_mixed_precision(mixed);

  build_materials();
  build_kernel();
  check_periodic_axes();
  build_bodies();
  build_stages();
  world_.refresh_material_index();
  build_writers();
}

Simulation::~Simulation() = default;  // here: ranks::Host is complete

int Simulation::run(const RunOptions& options) {
  if (options.threads > 0) omp_set_num_threads(options.threads);
  start_ranks();
  if (!options.restart.empty()) read_checkpoint(options.restart);
  spread_over_ranks(!options.restart.empty());
  const bool root = ranks::rank() == 0;  // the rank that writes and prints

  // Output folder: created only now that every input check has passed.
  output_directory_ = options.output_directory.empty() ? "out/" + scene_.name : options.output_directory;
  std::error_code ec;
  fs::create_directories(output_directory_, ec);
  if (ec) throw RunError("error: cannot create output folder " + output_directory_ + ": " + ec.message());
  if (access(output_directory_.c_str(), W_OK) != 0)
    throw RunError("error: output folder " + output_directory_ + " is not writable: " + std::strerror(errno));

  OutputContext context{output_directory_, scene_.name, scene_.text, TALUS_VERSION_STRING, !options.restart.empty()};
  for (auto& w : writers_)
    if (runs_here(w)) w.writer->open(context, world_);

  const ParamValues& time = scene_.values.object("time");
  const double dt_max = time.has("dt_max") ? time.real("dt_max") : std::numeric_limits<double>::infinity();
  const std::uint64_t max_steps =
      time.has("max_steps") ? static_cast<std::uint64_t>(time.integer("max_steps")) : std::numeric_limits<std::uint64_t>::max();

  // Checkpoint schedule.
  double checkpoint_every = 0.0, checkpoint_minutes = 0.0;
  std::size_t checkpoint_keep = 2;
  if (scene_.values.has("checkpoint")) {
    const ParamValues& c = scene_.values.object("checkpoint");
    if (c.has("every")) checkpoint_every = c.real("every");
    if (c.has("every_minutes")) checkpoint_minutes = c.real("every_minutes");
    checkpoint_keep = static_cast<std::size_t>(c.integer("keep"));
  }
  std::vector<std::string> checkpoints;
  auto checkpoint = [&]() {
    std::ostringstream name;
    name << output_directory_ << "/" << scene_.name << "_" << std::setw(8) << std::setfill('0') << world_.step
         << ".checkpoint";
    write_checkpoint(name.str());
    checkpoints.push_back(name.str());
    while (checkpoints.size() > checkpoint_keep) {
      if (root) fs::remove(checkpoints.front(), ec);
      checkpoints.erase(checkpoints.begin());
    }
    return name.str();
  };
  // Checkpoints fall on multiples of `every`, so a restarted run keeps the schedule.
  const double time_eps = checkpoint_every > 0 ? schedule_eps(world_.end_time, checkpoint_every) : 0.0;
  double next_checkpoint_time =
      checkpoint_every > 0 ? (std::floor(world_.time / checkpoint_every + 1e-9) + 1.0) * checkpoint_every : 0.0;

  // SIGINT/SIGTERM end the run after the current step, with a checkpoint; the
  // previous handlers are back when run() returns.
  const StopSignals stop_signals;

  Progress progress(options.quiet || !root, options.progress_seconds);
  auto count_over_ranks = [&](const ParticleStore& store) {
    const std::size_t own = store.owned_size();
    return ranks_ ? static_cast<std::size_t>(ranks_->sum(static_cast<std::uint64_t>(own))) : own;
  };
  const std::uint64_t first_step = world_.step;
  std::uint64_t particle_steps = 0, wall_particle_steps = 0;
  double wall_at_last_checkpoint = 0.0;
  phases_.stages.assign(stages_.size(), 0.0);
  phases_.setup += since_start_.lap();
  if (options.restart.empty()) write_due_outputs(true);
  phases_.outputs += since_start_.lap();
  const std::size_t fluid_at_start = count_over_ranks(world_.fluid), walls_at_start = count_over_ranks(world_.boundary);
  if (!options.quiet && root)
    std::printf("talus: running %s%s: %zu fluid particles, %zu wall particles%s, to t = %s s; output in %s\n",
                scene_.path.c_str(),
                ranks_ ? (" on " + std::to_string(ranks_->ranks()) + " MPI ranks").c_str() : "", fluid_at_start,
                walls_at_start,
                world_.blocks ? (", " + std::to_string(world_.blocks->size()) + " blocks").c_str() : "",
                fixed(world_.end_time).c_str(), output_directory_.c_str());
  if (!options.quiet && root && world_.fluid.mixed_precision())
    std::printf("talus: mixed precision: in float: fluid %s; walls %s\n",
                fields_in_float(world_.fluid).c_str(), fields_in_float(world_.boundary).c_str());
  print_new_warnings();

  try {
    while (world_.time < world_.end_time * (1.0 - 1e-12) && world_.step < max_steps) {
      phases_.host += since_start_.lap();
      double dt = std::min(dt_max, world_.end_time - world_.time);
      for (std::size_t i = 0; i < stages_.size(); ++i) {  // a stage may evaluate its rates for its bound
        dt = std::min(dt, stages_[i]->stable_time_step(world_));
        phases_.stages[i] += since_start_.lap();
      }
      if (ranks_) dt = ranks_->min(dt);
      if (!(dt > 0.0) || !std::isfinite(dt))
        throw RunError("error: step " + std::to_string(world_.step) + " (t = " + fixed(world_.time, 6) +
                       " s): the stages report no usable time step (dt = " + text::number(dt) + ")");
      for (std::size_t i = 0; i < stages_.size(); ++i) {
        stages_[i]->advance(world_, dt);
        phases_.stages[i] += since_start_.lap();
      }
      world_.time += dt;
      ++world_.step;
      particle_steps += world_.fluid.owned_size();
      wall_particle_steps += world_.boundary.owned_size();
      if (ranks_) {
        rank_upkeep(world_.step % resort_every_ == 0);
      } else {
        remove_escaped_particles();
        if (world_.step % resort_every_ == 0) resort_particles();
      }
      check_finite();
      phases_.host += since_start_.lap();
      write_due_outputs(false);
      share_warnings();
      print_new_warnings();
      // Every rank must take the checkpoint at the same step: clocks differ, rank 0's decides.
      bool minutes_due = checkpoint_minutes > 0 && progress.elapsed() - wall_at_last_checkpoint >= 60.0 * checkpoint_minutes;
      if (ranks_ && checkpoint_minutes > 0) minutes_due = ranks_->sum(root && minutes_due ? 1.0 : 0.0) > 0.0;
      if ((checkpoint_every > 0 && world_.time >= next_checkpoint_time - time_eps) || minutes_due) {
        checkpoint();
        wall_at_last_checkpoint = progress.elapsed();
        if (checkpoint_every > 0)
          next_checkpoint_time = next_due(next_checkpoint_time, checkpoint_every, world_.time, time_eps);
      }
      phases_.outputs += since_start_.lap();
      std::string status;
      if (options.verbose)
        for (std::size_t i = 0; i < stages_.size(); ++i) {
          const std::string st = stages_[i]->status(world_);
          if (!st.empty()) status += (status.empty() ? "" : "  ") + stage_names_[i] + ": " + st;
        }
      progress.update(world_.time, world_.end_time, dt, world_.step, ranks_ ? fluid_over_ranks_ : world_.fluid.size(),
                      status);
      // A signal that reached any rank stops every rank after this step.
      int sig = stop_signals.caught();
      if (ranks_) sig = static_cast<int>(ranks_->max(static_cast<double>(sig)));
      if (sig) {
        progress.finish();
        write_due_outputs(true);
        share_warnings();
        print_new_warnings();
        const std::string path = checkpoint();
        close_writers();
        if (!root) return 128 + sig;
        // The resume command repeats the options that shape the run (threads: the same result bit for bit;
        // another rank count gives it to round-off).
        const std::string threads = options.threads > 0 ? " --threads " + std::to_string(options.threads) : "";
        const std::string mpirun = ranks_ ? "mpirun -np " + std::to_string(ranks_->ranks()) + " " : "";
        std::printf("talus: stopped by %s at step %llu (t = %s s); checkpoint written.\n"
                    "       resume with: %stalus run %s --out %s --restart %s%s\n",
                    sig == SIGINT ? "SIGINT" : "SIGTERM", static_cast<unsigned long long>(world_.step),
                    fixed(world_.time, 6).c_str(), mpirun.c_str(), scene_.path.c_str(), output_directory_.c_str(),
                    path.c_str(), threads.c_str());
        return 128 + sig;
      }
    }
  } catch (const RunError&) {
    progress.finish();
    print_new_warnings();
    for (auto& w : writers_) {
      if (!runs_here(w)) continue;
      try {
        w.writer->close(world_);
      } catch (const std::exception&) {
      }
    }
    throw;
  }
  progress.finish();
  phases_.host += since_start_.lap();
  if (last_output_time_ < world_.time) write_due_outputs(true);
  RankFigures rank_figures;
  rank_figures.peak_memory_mib_max = peak_memory_mib();
  if (ranks_) {  // the summary counts every rank's particles and steps
    rank_figures = figures_over_ranks(particle_steps);
    particle_steps = ranks_->sum(static_cast<std::uint64_t>(particle_steps));
    wall_particle_steps = ranks_->sum(static_cast<std::uint64_t>(wall_particle_steps));
    world_.removed = ranks_->sum(static_cast<std::uint64_t>(world_.removed));
    world_.wall_crossings = ranks_->sum(static_cast<std::uint64_t>(world_.wall_crossings));
    gather_for_writers();
  }
  close_writers();
  share_warnings();
  print_new_warnings();
  std::vector<std::string> finish_lines;
  for (auto& stage : stages_)
    for (auto& line : stage->finish(world_, output_directory_)) finish_lines.push_back(line);
  phases_.outputs += since_start_.lap();

  const double wall = progress.elapsed();
  const RunSummary summary{scene_.path, world_, stages_, stage_names_, writers_, finish_lines,
                           world_.step - first_step, particle_steps, wall_particle_steps, wall, peak_memory_mib(),
                           phases_, rank_figures};
  if (!root) return 0;
  if (!options.summary_file.empty()) write_summary_file(summary, options.summary_file);
  if (!options.quiet) print_summary(summary);
  return 0;
}

}  // namespace talus
