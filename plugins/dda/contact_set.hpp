// The contact points of one step as structure-of-arrays, sorted by
// (model, block a, block b, feature) so that each contact model's batch is
// contiguous and the history of the previous step can be merged in one pass.
#pragma once

#include <cstdint>
#include <tuple>
#include <vector>

#include "talus/dda/contact_model.hpp"
#include "talus/vec3.hpp"

namespace talus::dda {

struct ContactKey {
  std::uint32_t model = 0, a = 0, b = 0;
  std::uint64_t feature = 0;
  friend bool operator<(const ContactKey& x, const ContactKey& y) {
    return std::tie(x.model, x.a, x.b, x.feature) < std::tie(y.model, y.a, y.b, y.feature);
  }
  friend bool operator==(const ContactKey& x, const ContactKey& y) = default;
};

class ContactSet {
 public:
  std::size_t size() const { return key.size(); }
  void resize(std::size_t n);

  // Copies the history (shear spring, state) of every contact of `previous`
  // whose key is also here; new contacts get `fresh_state(model)`.
  template <class FreshState>
  void inherit(const ContactSet& previous, FreshState&& fresh_state) {
    std::size_t p = 0;
    for (std::size_t c = 0; c < size(); ++c) {
      while (p < previous.size() && previous.key[p] < key[c]) ++p;
      if (p < previous.size() && previous.key[p] == key[c]) {
        shear[c] = previous.shear[p];
        state[c] = previous.state[p];
        ++p;
      } else {
        shear[c] = {};
        state[c] = fresh_state(key[c].model);
      }
    }
  }

  // The batch view of contacts [begin, end).
  ContactBatch batch(std::size_t begin, std::size_t end);

  std::vector<ContactKey> key;
  std::vector<Vec3> point, normal, velocity, shear, force;
  std::vector<double> gap, area, mass, strain_energy, dissipated;
  std::vector<std::uint8_t> state;
};

}  // namespace talus::dda
