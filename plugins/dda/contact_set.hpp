// The contact points of one step as structure-of-arrays, sorted by
// (model, block a, block b, feature) so that each contact model's batch is
// contiguous and the history of the previous step can be merged in one pass.
#pragma once

#include <algorithm>
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
  // Keeps the contacts whose flag is set, in their order.
  void keep(const std::vector<std::uint8_t>& flag);

  // Copies the history (shear spring, state) of every contact of `previous`
  // whose key is also here. A contact whose key is new takes the history of
  // the nearest unmatched previous contact of the same block pair within
  // `tolerance` (m): the clipped manifold of a resting contact may relabel its
  // points (a reference face swapped between coplanar faces), and a reset
  // spring would let the block slip and re-stick for ever. The rest get
  // `fresh_state(model)`.
  template <class FreshState>
  void inherit(const ContactSet& previous, FreshState&& fresh_state, double tolerance) {
    matched_.assign(previous.size(), 0);
    unmatched_.clear();
    std::size_t p = 0;
    for (std::size_t c = 0; c < size(); ++c) {
      while (p < previous.size() && previous.key[p] < key[c]) ++p;
      if (p < previous.size() && previous.key[p] == key[c]) {
        shear[c] = previous.shear[p];
        state[c] = previous.state[p];
        matched_[p] = 1;
        ++p;
      } else {
        unmatched_.push_back(c);
      }
    }
    for (const std::size_t c : unmatched_) {
      const ContactKey first{key[c].model, key[c].a, key[c].b, 0};
      std::size_t q = static_cast<std::size_t>(
          std::lower_bound(previous.key.begin(), previous.key.end(), first) - previous.key.begin());
      std::size_t best = previous.size();
      double best_distance = tolerance;
      for (; q < previous.size() && previous.key[q].model == first.model && previous.key[q].a == first.a &&
             previous.key[q].b == first.b;
           ++q) {
        const double d = norm(previous.point[q] - point[c]);
        if (!matched_[q] && d <= best_distance) {
          best = q;
          best_distance = d;
        }
      }
      if (best < previous.size()) {
        shear[c] = previous.shear[best];
        state[c] = previous.state[best];
        matched_[best] = 1;
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

 private:
  template <class F>
  void for_each_column(F&& f) {
    f(key), f(point), f(normal), f(velocity), f(shear), f(force);
    f(gap), f(area), f(mass), f(strain_energy), f(dissipated), f(state);
  }

  std::vector<std::uint8_t> matched_;     // scratch of inherit()
  std::vector<std::size_t> unmatched_;
};

}  // namespace talus::dda
