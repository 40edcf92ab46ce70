#include "slip_path.hpp"

#include <numeric>

namespace talus::strength_reduction {
namespace {

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t root(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent[root(a)] = root(b); }
};

}  // namespace

Release released_blocks(const BlockSet& blocks, const dda::ContactSet& contacts,
                        const std::vector<std::uint32_t>& rigid_body) {
  const std::size_t n = blocks.size();
  // Node n stands for the ground: every block that does not move by forces.
  UnionFind sets(n + 1);
  for (std::size_t i = 0; i < n; ++i)
    if (blocks.fixed[i] || blocks.kinematic[i]) sets.join(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(n));
  for (std::size_t i = 0; i < n; ++i) sets.join(static_cast<std::uint32_t>(i), rigid_body[i]);
  for (std::size_t c = 0; c < contacts.size(); ++c)
    if ((contacts.state[c] & dda::contact_state_mask) == dda::contact_stick)
      sets.join(contacts.key[c].a, contacts.key[c].b);
  Release r;
  double free_mass = 0.0, released_mass = 0.0;
  const std::uint32_t ground = sets.root(static_cast<std::uint32_t>(n));
  for (std::size_t i = 0; i < n; ++i) {
    if (blocks.fixed[i] || blocks.kinematic[i]) continue;
    free_mass += blocks.mass[i];
    if (sets.root(static_cast<std::uint32_t>(i)) != ground) {
      r.blocks.push_back(static_cast<std::uint32_t>(i));
      released_mass += blocks.mass[i];
    }
  }
  r.mass_fraction = free_mass > 0.0 ? released_mass / free_mass : 0.0;
  return r;
}

}  // namespace talus::strength_reduction
