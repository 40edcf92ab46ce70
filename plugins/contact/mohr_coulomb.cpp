#include "mohr_coulomb.hpp"

#include "penalty_coulomb.hpp"

namespace talus::contact {

ParamSet MohrCoulomb::describe() {
  ParamSet p{"mohr_coulomb", "penalty springs with a Mohr-Coulomb joint: cohesion and tensile strength that break"};
  declare_springs(p);
  p.real("cohesion").unit("Pa").min(0.0).default_value(0.0).doc("joint cohesion c, on the contact area");
  p.real("tensile_strength").unit("Pa").min(0.0).default_value(0.0).doc("joint tensile strength sigma_t");
  p.choice("shear_softening", {"brittle", "none"}).default_value("brittle")
      .doc("brittle: a bonded contact loses its cohesion and tensile strength at its first shear slip; none: it "
           "keeps its cohesion while it slips (perfectly plastic Mohr-Coulomb, as strength reduction assumes); "
           "a tensile failure breaks the bond either way");
  return p;
}

MohrCoulomb::MohrCoulomb(const ParamValues& v) : p_(read_springs(v)) {
  p_.cohesion = v.real("cohesion");
  p_.tensile_strength = v.real("tensile_strength");
  p_.brittle = v.string("shear_softening") == "brittle";
}

double MohrCoulomb::max_stiffness() const { return contact::max_stiffness(p_); }

std::uint8_t MohrCoulomb::initial_state() const { return contact::initial_state(p_); }

void MohrCoulomb::compute(const dda::ContactBatch& batch, double dt) const { joint_law(p_, batch, dt); }

}  // namespace talus::contact
