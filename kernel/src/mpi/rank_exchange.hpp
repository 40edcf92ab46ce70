// Particles spread over MPI ranks: Zoltan's cuts (zoltan_cuts.hpp) say which
// rank owns which place; this class moves whole particles to their owners,
// copies the particles near another rank's region into that rank's halo, and
// refreshes halo fields on request (talus/parallel.hpp). Every store's fields
// travel by the store's own metadata, so a plugin's fields move without it
// knowing.
#pragma once

#include <mpi.h>

#include <array>
#include <span>
#include <string>
#include <vector>

#include "talus/parallel.hpp"
#include "talus/particles.hpp"
#include "talus/vec3.hpp"
#include "zoltan_cuts.hpp"

namespace talus::mpi {

struct ExchangeSettings {
  int dim = 3;
  Vec3 lo{}, hi{};  // the domain
  std::array<bool, 3> periodic{};
  double cell = 0.0;   // the cuts keep cells of this size whole
  double reach = 0.0;  // halo width: the search radius plus the skin particles may move before the next rebuild
  std::string method = "RCB";
  double imbalance = 1.1;
};

class TALUS_API RankExchange final : public Parallel {
 public:
  RankExchange(MPI_Comm comm, const ExchangeSettings& settings);

  int rank() const override { return rank_; }
  int ranks() const override { return ranks_; }
  double sum(double local) const override;
  void sum(std::span<double> local) const override;
  std::uint64_t sum(std::uint64_t local) const override;
  double max(double local) const override;
  double min(double local) const override;
  std::uint64_t sum_before(std::uint64_t local) const override;
  int communicator() const override { return static_cast<int>(MPI_Comm_c2f(comm_)); }
  void refresh_halo(ParticleStore& store, std::span<const std::string> fields) override;

  // For stores that every rank built whole (`whole`), the same particles in
  // the same order: keeps this rank's share, then balances; otherwise each
  // rank's share is already its own and is only balanced. weights: cost of one
  // particle of each store.
  void scatter(std::span<ParticleStore* const> stores, std::span<const float> weights, bool whole = true);
  // New cuts from the particles' places and costs (one per owned row, the
  // stores' rows in turn); moves every particle to its new owner.
  void balance(std::span<ParticleStore* const> stores, std::span<const float> cost);
  // Moves every particle to the owner of its place under the current cuts.
  void migrate(std::span<ParticleStore* const> stores);
  // Drops every halo, then copies each owned particle within `reach` of another
  // rank's region into that rank's halo. With row groups for a store (one of
  // `group_count[s]` per owned row; the same count on every rank), its halo
  // holds group 0's rows from every rank, then group 1's, and so on, so that
  // a range of owned rows and a range of halo rows can be made to meet.
  void build_halos(std::span<ParticleStore* const> stores, std::span<const std::vector<std::uint8_t>> groups = {},
                   std::span<const int> group_count = {});
  void drop_halos(std::span<ParticleStore* const> stores);
  // For the writers: drops the halos and appends a copy of every other rank's
  // particles to rank 0's stores, in rank order; release_gathered() takes the
  // copies off again (the halos are then rebuilt by the caller).
  void gather_to_root(std::span<ParticleStore* const> stores);
  void release_gathered(std::span<ParticleStore* const> stores);
  // Rank 0 gets every rank's texts, in rank order; the others get none.
  std::vector<std::string> gather_texts(const std::vector<std::string>& texts) const;
  // Every rank gets every rank's values in rank order; each gives as many.
  std::vector<std::uint64_t> all_gather(std::span<const std::uint64_t> mine) const;

  // The place the cuts see for a particle: the centre of its cell.
  Vec3 cell_centre(const Vec3& x) const;

 private:
  struct HaloPlan {
    const ParticleStore* store = nullptr;
    std::size_t first = 0;                     // its first halo row, counted from the store's owned_size()
    std::vector<int> neighbours;               // ranks this rank sends to or receives from, ascending
    std::vector<std::vector<Index>> send;      // rows sent to each neighbour
    std::vector<std::size_t> receive;          // halo rows from each neighbour, in neighbour order
  };
  // Moves the rows whose destination is another rank there; received rows go last.
  void move(ParticleStore& store, std::span<const int> destination);
  // Sends packets[k] to neighbours[k] and receives into inbox[k] (sizes known).
  void swap_packets(std::span<const int> neighbours, std::span<const std::vector<std::byte>> packets,
                    std::span<std::vector<std::byte>> inbox) const;
  // Rank 0 gets every rank's bytes one after the other (counts and offsets per
  // rank in `counts`, `at`); the others get none.
  std::vector<std::byte> gather_bytes(std::span<const std::byte> mine, std::vector<int>& counts,
                                      std::vector<int>& at) const;
  // Other ranks whose region meets the box of half-width w about x, periodic images included.
  void ranks_near(const Vec3& x, double w, std::vector<int>& out) const;

  std::size_t nranks() const { return static_cast<std::size_t>(ranks_); }

  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  ExchangeSettings settings_;
  ZoltanCuts cuts_;
  std::vector<HaloPlan> plans_;
  std::vector<std::vector<std::byte>> packets_, inbox_;  // refresh_halo's, per neighbour (grow only)
  std::vector<std::size_t> own_before_gather_;  // rank 0: each store's own particles while gathered
};

}  // namespace talus::mpi
