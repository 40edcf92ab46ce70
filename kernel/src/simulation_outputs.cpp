// The writers' output schedule and the checkpoint files: what the writers
// have written, writing what is due, the run's warnings as they come, and
// saving and restoring the run state.
#include "simulation.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include "checkpoint.hpp"
#include "ranks.hpp"
#include "talus/number_text.hpp"
#include "output_schedule.hpp"
#include "talus/boundary.hpp"
#include "talus/error.hpp"
#include "talus/stage.hpp"
#include "talus/writer.hpp"

namespace talus {

std::vector<std::string> Simulation::output_files() const {
  std::vector<std::string> files;
  for (const auto& w : writers_)
    for (auto& f : w.writer->files()) files.push_back(f);
  return files;
}

std::vector<std::string> Simulation::output_results() const {
  std::vector<std::string> names;
  for (const auto& w : writers_)
    for (auto& name : w.writer->result_names()) names.push_back(w.type + "/" + name);
  return names;
}

std::vector<std::string> Simulation::output_series() const {
  std::vector<std::string> columns;
  for (const auto& w : writers_)
    for (auto& c : w.writer->series(world_)) columns.push_back(c);
  return columns;
}

// On stderr, so that --quiet and a redirected log keep them.
void Simulation::print_new_warnings() {
  if (ranks::rank() != 0) return;
  const auto& all = world_.warnings.all();
  for (; warnings_printed_ < all.size(); ++warnings_printed_)
    std::fprintf(stderr, "talus: warning: %s\n", all[warnings_printed_].c_str());
}

std::string Simulation::last_output() const {
  std::string newest;
  for (const auto& w : writers_) {
    const auto files = w.writer->files();
    if (!files.empty()) newest = files.back();
  }
  if (newest.empty()) return "none written yet";
  return newest + " (t = " + fixed(last_output_time_) + " s)";
}

bool Simulation::runs_here(const ScheduledWriter& w) const {
  return ranks::rank() == 0 || (ranks_ && w.writer->writes_on_every_rank());
}

void Simulation::close_writers() {
  for (auto& w : writers_)
    if (runs_here(w)) w.writer->close(world_);
}

// Every rank keeps the schedule. On several ranks the writers that share a
// file run on every rank first; the others run on rank 0 over a copy of every
// particle, gathered once for all of them that are due.
void Simulation::write_due_outputs(bool force) {
  auto eps = [&](const ScheduledWriter& w) { return w.every_steps ? 0.0 : schedule_eps(world_.end_time, w.every); };
  auto due = [&](const ScheduledWriter& w) {
    return force || (w.every_steps ? world_.step >= w.next_step : world_.time >= w.next_time - eps(w));
  };
  auto gathered = [&](const ScheduledWriter& w) { return ranks_ && !w.writer->writes_on_every_rank(); };
  if (std::none_of(writers_.begin(), writers_.end(), due)) return;
  const bool every_rank =
      ranks_ && std::any_of(writers_.begin(), writers_.end(), [&](const auto& w) { return due(w) && !gathered(w); });
  if (every_rank) refresh_halos_for_writers();
  for (auto& w : writers_)
    if (due(w) && !gathered(w)) w.writer->write(world_);
  const bool gather = std::any_of(writers_.begin(), writers_.end(), [&](const auto& w) { return due(w) && gathered(w); });
  if (gather) gather_for_writers();
  for (auto& w : writers_) {
    if (!due(w)) continue;
    if (gathered(w) && ranks::rank() == 0) w.writer->write(world_);
    last_output_time_ = world_.time;
    if (w.every_steps) {
      while (w.next_step <= world_.step) w.next_step += w.every_steps;
    } else {
      w.next_time = next_due(w.next_time, w.every, world_.time, eps(w));
    }
  }
  if (gather) release_after_writers();
}

void Simulation::write_checkpoint(const std::string& path) {
  RunState state;
  state.scene_hash = text_hash(scene_.text);
  for (const auto& s : stages_) state.stage_states.push_back(s->save_state());
  for (const Boundary* b : boundary_models()) state.boundary_states.push_back(b->save_state());
  for (const auto& w : writers_) {
    state.writer_next_time.push_back(w.next_time);
    state.writer_next_step.push_back(w.next_step);
  }
  state.last_output_time = last_output_time_;
  if (!ranks_) {
    save_checkpoint(path, world_, state);
    return;
  }
  // On several ranks they write the one file a serial run would together,
  // with every rank's count of removed particles.
  const std::uint64_t removed = world_.removed;
  world_.removed = ranks_->sum(removed);
  save_checkpoint_on_ranks(path, world_, state, *ranks_);
  world_.removed = removed;
}

void Simulation::read_checkpoint(const std::string& path) {
  RunState state = load_checkpoint(path, world_, text_hash(scene_.text), ranks_.get());
  const std::vector<Boundary*> boundaries = boundary_models();
  if (state.stage_states.size() != stages_.size())
    throw InputError("error: checkpoint " + path + ": it has the state of " + std::to_string(state.stage_states.size()) +
                     " stages, this scene's pipeline has " + std::to_string(stages_.size()));
  if (state.boundary_states.size() != boundaries.size())
    throw InputError("error: checkpoint " + path + ": it has the state of " +
                     std::to_string(state.boundary_states.size()) + " boundary models, this scene has " +
                     std::to_string(boundaries.size()));
  if (state.writer_next_time.size() != writers_.size())
    throw InputError("error: checkpoint " + path + ": it has the schedule of " +
                     std::to_string(state.writer_next_time.size()) + " outputs, this scene has " +
                     std::to_string(writers_.size()));
  // Models see only their bytes: the file and the model are named here.
  auto load = [&](auto& model, const std::string& bytes, const std::string& who) {
    try {
      model.load_state(bytes);
    } catch (const InputError& e) {
      std::string why = e.what();
      for (const char* prefix : {"error: checkpoint: ", "error: "})
        if (why.rfind(prefix, 0) == 0) {
          why.erase(0, std::strlen(prefix));
          break;
        }
      throw InputError("error: checkpoint " + path + ": " + who + ": " + why);
    }
  };
  for (std::size_t i = 0; i < stages_.size(); ++i)
    load(*stages_[i], state.stage_states[i], "stage " + std::to_string(i + 1) + " (" + stage_names_[i] + ")");
  for (std::size_t k = 0; k < boundaries.size(); ++k) {
    const auto body = std::ranges::find(world_.bodies, boundaries[k], &Body::boundary);
    load(*boundaries[k], state.boundary_states[k],
         "the boundary model of body '" + body->name + "' (" + body->params.pointer("boundary") + ")");
  }
  for (std::size_t i = 0; i < writers_.size(); ++i) {
    writers_[i].next_time = state.writer_next_time[i];
    writers_[i].next_step = state.writer_next_step[i];
  }
  last_output_time_ = state.last_output_time;
  // The wall models lay out their rows in the order they made them (ids
  // ascending), as a serial run keeps them; a run on several ranks wrote them
  // in rank order. (On several ranks this orders each rank's share.)
  const auto ids = world_.boundary.ids();
  if (!std::ranges::is_sorted(ids)) {
    std::vector<Index> order(ids.size());
    std::iota(order.begin(), order.end(), Index{0});
    std::ranges::sort(order, {}, [&](Index i) { return ids[i]; });
    world_.boundary.reorder(order);
  }
  world_.refresh_material_index();
}

}  // namespace talus
