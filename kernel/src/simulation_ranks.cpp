// A run spread over MPI ranks (`mpirun -np N talus run SCENE`): every rank
// builds the whole world from the scene, keeps its share, and between steps
// moves particles to their owners and rebuilds the halos when a particle has
// moved half the skin, one left the domain, or the re-sort is due. Writers
// that share a file (parallel HDF5) run on every rank; the others on rank 0
// over a gathered copy of every particle.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rank_cost.hpp"
#include "ranks.hpp"
#include "run_summary.hpp"
#include "simulation.hpp"
#include "store_rows.hpp"
#include "talus/boundary.hpp"
#include "talus/error.hpp"
#include "talus/stage.hpp"
#include "talus/number_text.hpp"
#include "talus/periodic.hpp"

namespace talus {

namespace {

// What runs on several ranks so far; the rest is refused before anything is written.
std::string unsupported_on_ranks(const World& world, const std::vector<std::unique_ptr<Stage>>& stages,
                                 const std::vector<std::string>& stage_names) {
  for (std::size_t i = 0; i < stages.size(); ++i)
    if (const std::string why = stages[i]->why_not_on_ranks(); !why.empty())
      return "/pipeline/" + std::to_string(i) + ": stage '" + stage_names[i] + "': " + why + "; such stages";
  // The ranks share out particles; blocks are stepped on every rank alike.
  if (world.fluid.size() == 0 && world.boundary.size() == 0)
    return "/bodies: no body has particles (blocks only); scenes without particles";
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    const Body& body = world.bodies[b];
    if (body.boundary)
      if (const std::string why = body.boundary->why_not_on_ranks(); !why.empty())
        return "/bodies/" + std::to_string(b) + "/boundary: " + to_string(body.kind) + " '" + body.name + "': " + why +
               "; such " + to_string(body.kind) + "s";
  }
  return {};
}

}  // namespace

void Simulation::start_ranks() {
  if (ranks::count() < 2) return;
  const std::string what = unsupported_on_ranks(world_, stages_, stage_names_);
  if (!what.empty())
    throw InputError("error: " + scene_.path + ": " + what + " do not run on several MPI ranks yet (" +
                     std::to_string(ranks::count()) + " were started); run this scene on one process");
  // The halo: one search radius, what a boundary model reads beyond it, and the skin.
  const double radius = world_.kernel.support_radius();
  double beyond = 0.0;
  for (const Boundary* model : boundary_models()) beyond = std::max(beyond, model->reach_beyond_radius());
  skin_ = world_.dp;
  std::string partition = "RCB";
  if (scene_.values.has("ranks")) {
    const ParamValues& r = scene_.values.object("ranks");
    partition = r.string("partition");
    rebalance_above_ = r.real("rebalance_above");
  }
  // Cells of one spacing: the cuts never split one, and a finer grain than
  // the search radius lets RCB's straight cuts share out a small body evenly.
  ranks_ = ranks::make_host(world_, skin_, radius + beyond + skin_, partition);
  world_.set_parallel(ranks_.get());
}

void Simulation::spread_over_ranks(bool restart) {
  if (!ranks_) return;
  // A restart read a share of the particles on each rank, and the run's count
  // of removed ones on every rank: rank 0 keeps the count, as each rank counts
  // its own from here.
  if (restart && ranks::rank() != 0) world_.removed = 0;
  ranks_->distribute(world_, !restart);
  rebuild_ranks();
}

void Simulation::rebuild_ranks() {
  ranks_->drop_halos(world_);
  ranks_->migrate(world_);
  settle_on_ranks();
  double imbalance = cost_imbalance();
  // Cuts that could not come within the threshold are made anew only when the
  // imbalance has grown by that factor again, not at every rebuild.
  const double trigger = cut_imbalance_ <= rebalance_above_ ? rebalance_above_ : cut_imbalance_ * rebalance_above_;
  if (imbalance > trigger) {
    ranks_->rebalance(world_, rank_cost_.costs());
    ++rebalances_;
    settle_on_ranks();
    imbalance = cost_imbalance();
    cut_imbalance_ = imbalance;
    if (imbalance > rebalance_above_ && !rebalance_warned_) {
      rebalance_warned_ = true;
      world_.warnings.add("step " + std::to_string(world_.step) + ": new cuts leave the busiest of " +
                          std::to_string(ranks_->ranks()) + " ranks " + fixed(imbalance) +
                          " times the mean cost, above /ranks/rebalance_above (" + fixed(rebalance_above_) +
                          "): the cuts never split a cell of one particle spacing, and a few cells here hold much "
                          "of a rank's share; new cuts follow when the imbalance grows by that factor again");
    }
  }
  worst_cost_imbalance_ = std::max(worst_cost_imbalance_, imbalance);
  cost_imbalance_now_ = imbalance;
  ++rebuilds_;
  fluid_over_ranks_ = static_cast<std::size_t>(ranks_->sum(static_cast<std::uint64_t>(world_.fluid.owned_size())));
  owned_rows_seen_ += world_.fluid.owned_size() + world_.boundary.owned_size();
  halo_rows_seen_ += world_.fluid.halo_size() + world_.boundary.halo_size();
  // Wall particles with a prescribed motion move too: their halo copies must keep up.
  moved_from_.clear();
  for (const ParticleStore* store : {&world_.fluid, &world_.boundary}) {
    const auto x = store->position();
    moved_from_.insert(moved_from_.end(), x.begin(), x.begin() + static_cast<std::ptrdiff_t>(store->owned_size()));
  }
}

void Simulation::settle_on_ranks() {
  resort_particles();
  ranks_->build_halos(world_);
  wall_rows_moved();
}

double Simulation::cost_imbalance() {
  double mine = 0.0;
  for (const float c : rank_cost_.measure(world_, world_.kernel.support_radius())) mine += c;
  return imbalance_over_ranks(mine);
}

double Simulation::imbalance_over_ranks(double mine) const {
  const double total = ranks_->sum(mine);
  const double busiest = ranks_->max(mine);
  return total > 0 ? busiest * ranks_->ranks() / total : 1.0;
}

void Simulation::rank_upkeep(bool resort_due) {
  cost_imbalance_steps_ += cost_imbalance_now_;  // the step just taken ran with it
  ++steps_on_ranks_;
  const std::uint64_t escaped = ranks_->sum(static_cast<std::uint64_t>(flag_escaped_particles()));
  Vec3 period{};
  for (int a = 0; a < 3; ++a)
    if (world_.periodic[a]) period[a] = world_.hi[a] - world_.lo[a];
  double moved = 0.0;
  std::size_t at = 0;  // moved_from_: the fluid's owned rows, then the walls'
  for (const ParticleStore* store : {&world_.fluid, &world_.boundary}) {
    const auto x = store->position();
    for (std::size_t i = 0; i < store->owned_size(); ++i, ++at)
      moved = std::max(moved, norm2(minimum_image(x[i] - moved_from_[at], period)));
  }
  moved = ranks_->max(std::sqrt(moved));
  if (escaped == 0 && !resort_due && moved < 0.5 * skin_) return;
  ranks_->drop_halos(world_);
  remove_flagged_particles();
  rebuild_ranks();
}

void Simulation::share_warnings() {
  if (!ranks_) return;
  const auto& all = world_.warnings.all();
  const std::vector<std::string> mine(all.begin() + static_cast<std::ptrdiff_t>(warnings_shared_), all.end());
  if (ranks_->sum(static_cast<std::uint64_t>(mine.size())) > 0)
    for (std::string& text : ranks_->gather_texts(mine)) world_.warnings.add(std::move(text));
  warnings_shared_ = world_.warnings.all().size();
}

RankFigures Simulation::figures_over_ranks(std::uint64_t own_particle_steps) const {
  RankFigures f;
  f.count = ranks_->ranks();
  f.imbalance = imbalance_over_ranks(static_cast<double>(own_particle_steps));
  const double owned = static_cast<double>(ranks_->sum(owned_rows_seen_));
  f.halo_share = owned > 0 ? static_cast<double>(ranks_->sum(halo_rows_seen_)) / owned : 0.0;
  f.rebuilds = rebuilds_;
  f.rebalances = rebalances_;
  f.cost_imbalance = worst_cost_imbalance_;
  f.cost_imbalance_mean = steps_on_ranks_ ? cost_imbalance_steps_ / steps_on_ranks_ : cost_imbalance_now_;
  f.peak_memory_mib_max = ranks_->max(peak_memory_mib());
  return f;
}

// The stages leave the halo copies as their own partial rates moved them
// (each evaluation refreshes them first); a writer on every rank that reads a
// particle's neighbours (the probes' wall forces) needs them as their owners have them.
void Simulation::refresh_halos_for_writers() {
  for (ParticleStore* store : {&world_.fluid, &world_.boundary}) ranks_->refresh_halo(*store, all_fields(*store));
}

void Simulation::gather_for_writers() {
  if (ranks_) ranks_->gather_to_root(world_);
}

void Simulation::release_after_writers() {
  if (!ranks_) return;
  ranks_->release_gathered(world_);
  ranks_->build_halos(world_);
  wall_rows_moved();
}

void Simulation::wall_rows_moved() {
  world_.refresh_material_index();
  for (Boundary* model : boundary_models()) model->rows_moved(world_);
}

}  // namespace talus
