#include "contact_set.hpp"

namespace talus::dda {

void ContactSet::resize(std::size_t n) {
  key.resize(n);
  point.resize(n);
  normal.resize(n);
  velocity.resize(n);
  shear.resize(n);
  force.resize(n);
  gap.resize(n);
  area.resize(n);
  mass.resize(n);
  strain_energy.resize(n);
  dissipated.resize(n);
  state.resize(n);
}

void ContactSet::keep(const std::vector<std::uint8_t>& flag) {
  std::size_t n = 0;
  for (std::size_t c = 0; c < size(); ++c) {
    if (!flag[c]) continue;
    key[n] = key[c];
    point[n] = point[c];
    normal[n] = normal[c];
    velocity[n] = velocity[c];
    shear[n] = shear[c];
    force[n] = force[c];
    gap[n] = gap[c];
    area[n] = area[c];
    mass[n] = mass[c];
    strain_energy[n] = strain_energy[c];
    dissipated[n] = dissipated[c];
    state[n] = state[c];
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
