#include "rank_exchange.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>

#include "../store_rows.hpp"

namespace talus::mpi {

namespace {

int message_size(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT_MAX))
    throw std::runtime_error("MPI: a message of " + std::to_string(bytes) + " bytes is over MPI's int count limit");
  return static_cast<int>(bytes);
}

// Appends the rows of every rank's packet (in[at[r], at[r] + bytes[r])) to the
// store in rank order; they keep the ids they travelled with.
void append_packets(ParticleStore& store, std::span<const std::string> fields, std::span<const std::byte> in,
                    std::span<const int> bytes, std::span<const int> at) {
  const std::size_t per_row = row_bytes(store, fields);
  const std::uint64_t next_id = store.next_id();
  std::size_t first = store.append(in.size() / per_row);
  store.set_next_id(next_id);
  for (std::size_t r = 0; r < bytes.size(); ++r) {
    const auto n = static_cast<std::size_t>(bytes[r]);
    unpack_rows(store, fields, in.subspan(static_cast<std::size_t>(at[r]), n), first, n / per_row);
    first += n / per_row;
  }
}

}  // namespace

RankExchange::RankExchange(MPI_Comm comm, const ExchangeSettings& settings)
    : comm_(comm), settings_(settings), cuts_(comm, settings.dim, settings.method, settings.imbalance) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &ranks_);
  if (!(settings_.cell > 0.0) || !(settings_.reach >= 0.0))
    throw std::logic_error("RankExchange: cell size and halo reach must be positive");
}

double RankExchange::sum(double local) const {
  std::vector<double> all(nranks());
  MPI_Allgather(&local, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, comm_);
  double total = 0.0;
  for (const double v : all) total += v;  // rank order: the same bits on every rank and every run
  return total;
}

void RankExchange::sum(std::span<double> local) const {
  const std::size_t n = local.size();
  std::vector<double> all(n * nranks());
  MPI_Allgather(local.data(), message_size(n), MPI_DOUBLE, all.data(), message_size(n), MPI_DOUBLE, comm_);
  for (std::size_t k = 0; k < n; ++k) {
    double total = 0.0;
    for (std::size_t r = 0; r < nranks(); ++r) total += all[r * n + k];
    local[k] = total;
  }
}

std::uint64_t RankExchange::sum(std::uint64_t local) const {
  std::uint64_t total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_UINT64_T, MPI_SUM, comm_);
  return total;
}

std::uint64_t RankExchange::sum_before(std::uint64_t local) const {
  std::uint64_t before = 0;
  MPI_Exscan(&local, &before, 1, MPI_UINT64_T, MPI_SUM, comm_);
  return rank_ == 0 ? 0 : before;  // MPI leaves rank 0's result undefined
}

double RankExchange::max(double local) const {
  double out = 0.0;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return out;
}

double RankExchange::min(double local) const {
  double out = 0.0;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MIN, comm_);
  return out;
}

Vec3 RankExchange::cell_centre(const Vec3& x) const {
  Vec3 c = x;
  for (int a = 0; a < settings_.dim; ++a)
    c[a] = settings_.lo[a] + (std::floor((x[a] - settings_.lo[a]) / settings_.cell) + 0.5) * settings_.cell;
  return c;
}

void RankExchange::scatter(std::span<ParticleStore* const> stores, std::span<const float> weights, bool whole) {
  std::vector<float> cost;
  for (std::size_t s = 0; s < stores.size(); ++s) {
    ParticleStore* store = stores[s];
    store->drop_halo();
    if (!whole) {
      cost.insert(cost.end(), store->size(), weights[s]);
      continue;
    }
    const std::size_t n = store->size();
    const std::size_t first = n * static_cast<std::size_t>(rank_) / nranks();
    const std::size_t last = n * static_cast<std::size_t>(rank_ + 1) / nranks();
    std::vector<std::uint8_t> drop(n, 1);
    std::fill(drop.begin() + static_cast<std::ptrdiff_t>(first), drop.begin() + static_cast<std::ptrdiff_t>(last), 0);
    store->remove_if(drop);
    cost.insert(cost.end(), store->size(), weights[s]);
  }
  balance(stores, cost);
}

void RankExchange::balance(std::span<ParticleStore* const> stores, std::span<const float> cost) {
  drop_halos(stores);
  std::vector<Vec3> places;
  for (ParticleStore* store : stores)
    for (const Vec3& p : store->position()) places.push_back(cell_centre(p));
  if (cost.size() != places.size()) throw std::logic_error("RankExchange::balance: a cost for every owned row");
  const std::vector<int> owner = cuts_.partition(places, cost);
  std::size_t at = 0;
  for (ParticleStore* store : stores) {
    const std::size_t n = store->size();
    move(*store, std::span<const int>(owner).subspan(at, n));
    at += n;
  }
}

void RankExchange::migrate(std::span<ParticleStore* const> stores) {
  if (!cuts_.has_cuts()) throw std::logic_error("RankExchange::migrate before the first balance");
  drop_halos(stores);
  for (ParticleStore* store : stores) {
    const auto x = store->position();
    std::vector<int> owner(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) owner[i] = cuts_.owner(cell_centre(x[i]));
    move(*store, owner);
  }
}

void RankExchange::move(ParticleStore& store, std::span<const int> destination) {
  const auto fields = all_fields(store);
  std::vector<std::vector<Index>> rows(nranks());
  std::vector<std::uint8_t> leaves(store.size(), 0);
  for (std::size_t i = 0; i < destination.size(); ++i)
    if (destination[i] != rank_) {
      rows[destination[i]].push_back(static_cast<Index>(i));
      leaves[i] = 1;
    }
  std::vector<std::byte> out;
  std::vector<int> send_bytes(nranks()), send_at(nranks());
  for (std::size_t r = 0; r < nranks(); ++r) {
    const std::size_t before = out.size();
    pack_rows(store, fields, rows[r], out);
    send_at[r] = message_size(before);
    send_bytes[r] = message_size(out.size() - before);
  }
  std::vector<int> receive_bytes(nranks()), receive_at(nranks());
  MPI_Alltoall(send_bytes.data(), 1, MPI_INT, receive_bytes.data(), 1, MPI_INT, comm_);
  std::size_t total = 0;
  for (std::size_t r = 0; r < nranks(); ++r) {
    receive_at[r] = message_size(total);
    total += static_cast<std::size_t>(receive_bytes[r]);
  }
  std::vector<std::byte> in(total);
  MPI_Alltoallv(out.data(), send_bytes.data(), send_at.data(), MPI_BYTE, in.data(), receive_bytes.data(),
                receive_at.data(), MPI_BYTE, comm_);

  store.remove_if(leaves);
  append_packets(store, fields, in, receive_bytes, receive_at);
}

void RankExchange::ranks_near(const Vec3& x, double w, std::vector<int>& out) const {
  // Periodic images of the box: a shift by the period on each axis the box crosses.
  std::array<std::vector<double>, 3> shifts;
  for (int a = 0; a < 3; ++a) {
    shifts[a] = {0.0};
    if (a >= settings_.dim || !settings_.periodic[a]) continue;
    const double period = settings_.hi[a] - settings_.lo[a];
    if (x[a] - w < settings_.lo[a]) shifts[a].push_back(period);
    if (x[a] + w > settings_.hi[a]) shifts[a].push_back(-period);
  }
  const std::size_t start = out.size();
  for (const double sx : shifts[0])
    for (const double sy : shifts[1])
      for (const double sz : shifts[2]) {
        const Vec3 c{x.x + sx, x.y + sy, x.z + sz};
        cuts_.ranks_meeting({c.x - w, c.y - w, c.z - w}, {c.x + w, c.y + w, c.z + w}, out);
      }
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(start), out.end());
  out.erase(std::unique(out.begin() + static_cast<std::ptrdiff_t>(start), out.end()), out.end());
  out.erase(std::remove(out.begin() + static_cast<std::ptrdiff_t>(start), out.end(), rank_), out.end());
}

void RankExchange::drop_halos(std::span<ParticleStore* const> stores) {
  for (ParticleStore* store : stores) store->drop_halo();
  plans_.clear();
}

void RankExchange::build_halos(std::span<ParticleStore* const> stores, std::span<const std::vector<std::uint8_t>> groups,
                               std::span<const int> group_count) {
  drop_halos(stores);
  // An owned particle's cell centre is inside this rank's region, at most half
  // a cell from the particle on each axis: the box reaches that much further.
  const double w = settings_.reach + 0.5 * settings_.cell;
  for (std::size_t s = 0; s < stores.size(); ++s) {
    ParticleStore* store = stores[s];
    const bool grouped = s < groups.size() && !groups[s].empty();
    const int count = grouped ? group_count[s] : 1;
    if (grouped && groups[s].size() != store->size())
      throw std::logic_error("RankExchange::build_halos: a row group for every owned row");
    std::vector<std::vector<std::vector<Index>>> send(count, std::vector<std::vector<Index>>(nranks()));
    std::vector<int> near;
    const auto x = store->position();
    for (std::size_t i = 0; i < x.size(); ++i) {
      near.clear();
      ranks_near(x[i], w, near);
      const int g = grouped ? groups[s][i] : 0;
      for (const int r : near) send[g][static_cast<std::size_t>(r)].push_back(static_cast<Index>(i));
    }
    std::size_t halo = 0;
    for (int g = 0; g < count; ++g) {
      HaloPlan plan;
      plan.store = store;
      plan.first = halo;
      std::vector<std::uint64_t> send_count(nranks()), receive_count(nranks());
      for (std::size_t r = 0; r < nranks(); ++r) send_count[r] = send[g][r].size();
      MPI_Alltoall(send_count.data(), 1, MPI_UINT64_T, receive_count.data(), 1, MPI_UINT64_T, comm_);
      for (std::size_t r = 0; r < nranks(); ++r)
        if (send_count[r] > 0 || receive_count[r] > 0) {
          plan.neighbours.push_back(static_cast<int>(r));
          plan.send.push_back(std::move(send[g][r]));
          plan.receive.push_back(receive_count[r]);
          halo += receive_count[r];
        }
      plans_.push_back(std::move(plan));
    }
    store->append_halo(halo);
    refresh_halo(*store, all_fields(*store));
  }
}

void RankExchange::gather_to_root(std::span<ParticleStore* const> stores) {
  drop_halos(stores);
  own_before_gather_.clear();
  for (ParticleStore* store : stores) {
    own_before_gather_.push_back(store->size());
    const auto fields = all_fields(*store);
    std::vector<std::byte> mine;
    if (rank_ != 0) {
      std::vector<Index> rows(store->size());
      std::iota(rows.begin(), rows.end(), Index{0});
      pack_rows(*store, fields, rows, mine);
    }
    std::vector<int> counts, at;
    const std::vector<std::byte> in = gather_bytes(mine, counts, at);
    if (rank_ == 0) append_packets(*store, fields, in, counts, at);  // rank 0's own packet is empty
  }
}

std::vector<std::byte> RankExchange::gather_bytes(std::span<const std::byte> mine, std::vector<int>& counts,
                                                  std::vector<int>& at) const {
  const int bytes = message_size(mine.size());
  counts.assign(nranks(), 0);
  at.assign(nranks(), 0);
  MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
  std::size_t total = 0;
  for (std::size_t r = 0; r < nranks(); ++r) {
    at[r] = message_size(total);
    total += static_cast<std::size_t>(counts[r]);
  }
  std::vector<std::byte> in(rank_ == 0 ? total : 0);
  MPI_Gatherv(mine.data(), bytes, MPI_BYTE, in.data(), counts.data(), at.data(), MPI_BYTE, 0, comm_);
  return in;
}

std::vector<std::uint64_t> RankExchange::all_gather(std::span<const std::uint64_t> mine) const {
  std::vector<std::uint64_t> all(mine.size() * nranks());
  MPI_Allgather(mine.data(), message_size(mine.size()), MPI_UINT64_T, all.data(), message_size(mine.size()),
                MPI_UINT64_T, comm_);
  return all;
}

std::vector<std::string> RankExchange::gather_texts(const std::vector<std::string>& texts) const {
  std::string mine;  // each text ends with a NUL
  for (const std::string& t : texts) {
    mine += t;
    mine.push_back('\0');
  }
  std::vector<int> counts, at;
  const std::vector<std::byte> bytes = gather_bytes(std::as_bytes(std::span(mine)), counts, at);
  const std::string in(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  std::vector<std::string> out;
  for (std::size_t begin = 0, end; (end = in.find('\0', begin)) != std::string::npos; begin = end + 1)
    out.emplace_back(in, begin, end - begin);
  return out;
}

void RankExchange::release_gathered(std::span<ParticleStore* const> stores) {
  if (own_before_gather_.size() != stores.size())
    throw std::logic_error("RankExchange::release_gathered without gather_to_root");
  for (std::size_t s = 0; s < stores.size(); ++s) {
    std::vector<std::uint8_t> others(stores[s]->size(), 0);
    std::fill(others.begin() + static_cast<std::ptrdiff_t>(own_before_gather_[s]), others.end(), 1);
    stores[s]->remove_if(others);
  }
  own_before_gather_.clear();
}

void RankExchange::swap_packets(std::span<const int> neighbours, std::span<const std::vector<std::byte>> packets,
                                std::span<std::vector<std::byte>> inbox) const {
  std::vector<MPI_Request> requests;
  requests.reserve(2 * neighbours.size());
  for (std::size_t k = 0; k < neighbours.size(); ++k) {
    requests.emplace_back();
    MPI_Irecv(inbox[k].data(), message_size(inbox[k].size()), MPI_BYTE, neighbours[k], 0, comm_, &requests.back());
  }
  for (std::size_t k = 0; k < neighbours.size(); ++k) {
    requests.emplace_back();
    MPI_Isend(packets[k].data(), message_size(packets[k].size()), MPI_BYTE, neighbours[k], 0, comm_,
              &requests.back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

void RankExchange::refresh_halo(ParticleStore& store, std::span<const std::string> fields) {
  const std::size_t per_row = row_bytes(store, fields);
  for (const HaloPlan& plan : plans_) {
    if (plan.store != &store) continue;
    const std::size_t n = plan.neighbours.size();
    // The buffers keep their capacity from one refresh to the next.
    packets_.resize(std::max(packets_.size(), n));
    inbox_.resize(std::max(inbox_.size(), n));
    for (std::size_t k = 0; k < n; ++k) {
      packets_[k].clear();
      pack_rows(store, fields, plan.send[k], packets_[k]);
      inbox_[k].resize(plan.receive[k] * per_row);
    }
    swap_packets(plan.neighbours, std::span(packets_).first(n), std::span(inbox_).first(n));
    std::size_t first = store.owned_size() + plan.first;
    for (std::size_t k = 0; k < n; ++k) {
      unpack_rows(store, fields, inbox_[k], first, plan.receive[k]);
      first += plan.receive[k];
    }
  }
}

}  // namespace talus::mpi
