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
