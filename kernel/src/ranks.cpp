#include "ranks.hpp"

#include <array>
#include <cstdlib>

#if TALUS_WITH_MPI
#include <mpi.h>

#include "mpi/rank_exchange.hpp"
#endif

namespace talus::ranks {

#if TALUS_WITH_MPI

namespace {

bool started_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

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
  double max(double v) const override { return exchange_.max(v); }
  double min(double v) const override { return exchange_.min(v); }
  void refresh_halo(ParticleStore& store, std::span<const std::string> fields) override {
    exchange_.refresh_halo(store, fields);
  }
  void distribute(World& world) override { exchange_.scatter(stores_of(world), kStoreWeights); }
  void drop_halos(World& world) override { exchange_.drop_halos(stores_of(world)); }
  void migrate(World& world) override { exchange_.migrate(stores_of(world)); }
  void build_halos(World& world) override { exchange_.build_halos(stores_of(world)); }
  void gather_to_root(World& world) override { exchange_.gather_to_root(stores_of(world)); }
  void release_gathered(World& world) override { exchange_.release_gathered(stores_of(world)); }

 private:
  mpi::RankExchange exchange_;
};

}  // namespace

void start(int* argc, char*** argv) {
  if (!started_by_mpirun() || mpi_running()) return;
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
  std::exit(code);
}

std::unique_ptr<Host> make_host(const World& world, double cell, double halo_reach) {
  if (count() < 2) return nullptr;
  mpi::ExchangeSettings s;
  s.dim = world.dim;
  s.lo = world.lo;
  s.hi = world.hi;
  s.periodic = world.periodic;
  s.cell = cell;
  s.reach = halo_reach;
  return std::make_unique<ExchangeHost>(s);
}

#else

void start(int*, char***) {}
void stop() {}
int rank() { return 0; }
int count() { return 1; }
void abort_all(int code) { std::exit(code); }
std::unique_ptr<Host> make_host(const World&, double, double) { return nullptr; }

#endif

}  // namespace talus::ranks
