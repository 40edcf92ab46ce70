#include "mohr_coulomb.hpp"

#include <algorithm>

#include "penalty_coulomb.hpp"

namespace talus::contact {

ParamSet MohrCoulomb::describe() {
  ParamSet p{"mohr_coulomb", "penalty springs with a Mohr-Coulomb joint: cohesion and tensile strength that break"};
  declare_springs(p);
  p.real("cohesion").unit("Pa").min(0.0).default_value(0.0).doc("joint cohesion c, on the contact area");
  p.real("tensile_strength").unit("Pa").min(0.0).default_value(0.0).doc("joint tensile strength sigma_t");
  return p;
}

MohrCoulomb::MohrCoulomb(const ParamValues& v) : p_(read_springs(v)) {
  p_.cohesion = v.real("cohesion");
  p_.tensile_strength = v.real("tensile_strength");
}

double MohrCoulomb::max_stiffness() const { return std::max(p_.normal_stiffness, p_.shear_stiffness); }

std::uint8_t MohrCoulomb::initial_state() const {
  const bool bonded = p_.cohesion > 0.0 || p_.tensile_strength > 0.0;
  return bonded ? dda::contact_bonded : static_cast<std::uint8_t>(dda::contact_open);
}

void MohrCoulomb::compute(const dda::ContactBatch& batch, double dt) const { joint_law(p_, batch, dt); }

}  // namespace talus::contact
