#include "reduced_joint.hpp"

#include "mohr_coulomb.hpp"
#include "penalty_coulomb.hpp"

namespace talus::strength_reduction {

ReducedJoint::ReducedJoint(const std::string& model, const ParamValues& v, const ParamValues& body) {
  if (model == "mohr_coulomb")
    base_ = contact::MohrCoulomb(v).parameters();
  else if (model == "penalty_coulomb")
    base_ = contact::PenaltyCoulomb(v).parameters();
  else
    body.fail("contact", "strength reduction divides the joint strength of penalty_coulomb and mohr_coulomb "
                         "contacts; '" + model + "' is neither");
  reduced_ = base_;
}

void ReducedJoint::set_factor(double factor, bool unbreakable) {
  factor_ = factor;
  reduced_ = base_;
  reduced_.tan_friction = base_.tan_friction / factor;
  reduced_.cohesion = base_.cohesion / factor;
  // Finite, so that a contact without area (tensile capacity 0 x strength) stays a plain 0.
  reduced_.tensile_strength = unbreakable ? 1e30 : base_.tensile_strength / factor;
}

double ReducedJoint::max_stiffness() const { return contact::max_stiffness(base_); }

std::uint8_t ReducedJoint::initial_state() const { return contact::initial_state(base_); }

void ReducedJoint::compute(const dda::ContactBatch& batch, double dt) const { contact::joint_law(reduced_, batch, dt); }

}  // namespace talus::strength_reduction
