#include "contact_set.hpp"

namespace talus::dda {

void ContactSet::resize(std::size_t n) {
  for_each_column([n](auto& column) { column.resize(n); });
}

void ContactSet::keep(const std::vector<std::uint8_t>& flag) {
  std::size_t n = 0;
  for (std::size_t c = 0; c < size(); ++c)
    if (flag[c]) {
      for_each_column([c, n](auto& column) { column[n] = column[c]; });
      ++n;
    }
  resize(n);
}

ContactBatch ContactSet::batch(std::size_t begin, std::size_t end) {
  ContactBatch b;
  b.size = end - begin;
  b.gap = gap.data() + begin;
  b.normal = normal.data() + begin;
  b.velocity = velocity.data() + begin;
  b.area = area.data() + begin;
  b.mass = mass.data() + begin;
  b.shear = shear.data() + begin;
  b.state = state.data() + begin;
  b.force = force.data() + begin;
  b.strain_energy = strain_energy.data() + begin;
  b.dissipated = dissipated.data() + begin;
  return b;
}

}  // namespace talus::dda
