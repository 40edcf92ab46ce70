// The MPI side of ranks.hpp, in a library of its own (libtalus_ranks_mpi)
// that libtalus loads only in a process mpirun started: a run on one process
// never maps Open MPI, Zoltan and what they pull in.
#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <functional>
#include <numeric>

#include "mpi/rank_exchange.hpp"
#include "mpi/shared_file.hpp"
#include "ranks.hpp"

namespace talus::ranks {

namespace {

bool mpi_running() {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  return initialised && !finalised;
}

// The stores the ranks share out, in one order on every rank.
std::array<ParticleStore*, 2> stores_of(World& world) { return {&world.fluid, &world.boundary}; }

// Cost of a particle for the cuts: a wall particle takes part in fewer pairs
// than a fluid one and is not integrated by the fluid's scheme.
const float kStoreWeights[2] = {1.0f, 0.3f};

class ExchangeHost final : public Host {
 public:
  explicit ExchangeHost(const mpi::ExchangeSettings& s) : exchange_(MPI_COMM_WORLD, s) {}
  int rank() const override { return exchange_.rank(); }
  int ranks() const override { return exchange_.ranks(); }
  double sum(double v) const override { return exchange_.sum(v); }
  std::uint64_t sum(std::uint64_t v) const override { return exchange_.sum(v); }
  void sum(std::span<double> v) const override { exchange_.sum(v); }
  double max(double v) const override { return exchange_.max(v); }
  double min(double v) const override { return exchange_.min(v); }
  std::uint64_t sum_before(std::uint64_t v) const override { return exchange_.sum_before(v); }
  int communicator() const override { return exchange_.communicator(); }
  void refresh_halo(ParticleStore& store, std::span<const std::string> fields) override {
    exchange_.refresh_halo(store, fields);
  }
  void distribute(World& world, bool whole) override {
    exchange_.scatter(stores_of(world), kStoreWeights, whole);
  }
  void drop_halos(World& world) override { exchange_.drop_halos(stores_of(world)); }
  void migrate(World& world) override { exchange_.migrate(stores_of(world)); }
  void rebalance(World& world, std::span<const float> cost) override { exchange_.balance(stores_of(world), cost); }
  void build_halos(World& world) override;
  void gather_to_root(World& world) override { exchange_.gather_to_root(stores_of(world)); }
  void release_gathered(World& world) override { exchange_.release_gathered(stores_of(world)); }
  std::vector<std::string> gather_texts(const std::vector<std::string>& mine) override {
    return exchange_.gather_texts(mine);
  }
  std::vector<std::uint64_t> all_gather(std::span<const std::uint64_t> mine) const override {
    return exchange_.all_gather(mine);
  }
  std::unique_ptr<SharedFile> create_shared_file(const std::string& path) const override {
    return std::make_unique<mpi::SharedFile>(MPI_COMM_WORLD, path);
  }

 private:
  mpi::RankExchange exchange_;
};

// World.boundary's rows in groups: the block particles, whose models find
// them by body wherever they lie, and the wall particles of each wall model,
// which keeps its own as one run of owned rows and one of halo rows
// (Boundary::rows_moved). Owned rows: the blocks' first, then each wall
// model's in turn; halo rows: each wall model's in the same order, then the
// blocks'. The last wall model's owned rows and the first's halo rows meet,
// so with one wall model its rows, owned and halo, are one run.
void ExchangeHost::build_halos(World& world) {
  exchange_.drop_halos(stores_of(world));
  ParticleStore& boundary = world.boundary;
  std::vector<const Boundary*> wall_models;  // in the order of their first body
  std::vector<std::uint8_t> group_of_body(world.bodies.size(), 0);
  for (std::size_t b = 0; b < world.bodies.size(); ++b) {
    if (world.bodies[b].kind != BodyKind::wall) continue;
    const Boundary* model = world.bodies[b].boundary;
    auto it = std::find(wall_models.begin(), wall_models.end(), model);
    if (it == wall_models.end()) it = wall_models.insert(wall_models.end(), model);
    group_of_body[b] = static_cast<std::uint8_t>(it - wall_models.begin());
  }
  if (wall_models.size() > 254) throw RunError("error: more than 254 wall boundary models on several MPI ranks");
  const auto blocks = static_cast<std::uint8_t>(wall_models.size());
  for (std::size_t b = 0; b < world.bodies.size(); ++b)
    if (world.bodies[b].kind == BodyKind::block) group_of_body[b] = blocks;
  std::vector<std::uint8_t> group(boundary.size());
  const auto body = boundary.body();
  for (std::size_t i = 0; i < group.size(); ++i) group[i] = group_of_body[body[i]];
  // Owned: the blocks (the last group) first, then the wall models in order.
  auto owned_order = [&](std::uint8_t g) { return g == blocks ? -1 : static_cast<int>(g); };
  if (!std::is_sorted(group.begin(), group.end(), [&](auto a, auto b) { return owned_order(a) < owned_order(b); })) {
    std::vector<Index> order(group.size());
    std::iota(order.begin(), order.end(), Index{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](Index a, Index b) { return owned_order(group[a]) < owned_order(group[b]); });
    boundary.reorder(order);
    std::vector<std::uint8_t> sorted(group.size());
    for (std::size_t i = 0; i < order.size(); ++i) sorted[i] = group[order[i]];
    group = std::move(sorted);
  }
  const std::vector<std::uint8_t> groups[2] = {{}, std::move(group)};
  const int group_count[2] = {1, blocks + 1};
  exchange_.build_halos(stores_of(world), groups, group_count);
}

void start(int* argc, char*** argv) {
  if (mpi_running()) return;
  int provided = 0;
  // OpenMP threads inside a rank; MPI is called from the main thread only.
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
}

void stop() {
  if (mpi_running()) MPI_Finalize();
}

int rank() {
  int r = 0;
  if (mpi_running()) MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int count() {
  int n = 1;
  if (mpi_running()) MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

void abort_all(int code) {
  if (mpi_running()) MPI_Abort(MPI_COMM_WORLD, code);
}

std::unique_ptr<Host> make_host(const World& world, double cell, double halo_reach, const std::string& partition) {
  mpi::ExchangeSettings s;
  s.dim = world.dim;
  s.lo = world.lo;
  s.hi = world.hi;
  s.periodic = world.periodic;
  s.cell = cell;
  s.reach = halo_reach;
  s.method = partition;
  return std::make_unique<ExchangeHost>(s);
}

const Backend mpi_backend{start, stop, rank, count, abort_all, make_host};

}  // namespace

}  // namespace talus::ranks

extern "C" TALUS_API const talus::ranks::Backend* talus_ranks_backend() { return &talus::ranks::mpi_backend; }
