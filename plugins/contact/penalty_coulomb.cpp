#include "penalty_coulomb.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace talus::contact {

void declare_springs(ParamSet& p) {
  p.real("normal_stiffness").unit("N/m").greater_than(0.0).doc("penalty spring stiffness of one contact point");
  p.real("shear_stiffness").unit("N/m").greater_than(0.0).optional()
      .doc("shear spring stiffness of one contact point (default 0.4 x normal_stiffness)");
  p.real("friction_angle").unit("deg").min(0.0).less_than(90.0).doc("Coulomb friction angle phi of the joint");
  p.real("damping_ratio").min(0.0).max(1.0).default_value(0.2)
      .doc("viscous contact damping as a fraction of critical (per manifold, normal and sticking shear)");
}

JointParameters read_springs(const ParamValues& v) {
  JointParameters p;
  p.normal_stiffness = v.real("normal_stiffness");
  p.shear_stiffness = v.has("shear_stiffness") ? v.real("shear_stiffness") : 0.4 * p.normal_stiffness;
  p.tan_friction = std::tan(v.real("friction_angle") * std::numbers::pi / 180.0);
  p.damping_ratio = v.real("damping_ratio");
  return p;
}

ParamSet PenaltyCoulomb::describe() {
  ParamSet p{"penalty_coulomb", "DDA penalty contact springs with Coulomb friction and contact damping"};
  declare_springs(p);
  return p;
}

PenaltyCoulomb::PenaltyCoulomb(const ParamValues& v) : p_(read_springs(v)) {}

double PenaltyCoulomb::max_stiffness() const { return contact::max_stiffness(p_); }

void PenaltyCoulomb::compute(const dda::ContactBatch& batch, double dt) const { joint_law(p_, batch, dt); }

}  // namespace talus::contact
