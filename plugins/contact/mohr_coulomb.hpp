// mohr_coulomb: the penalty_coulomb springs plus a Mohr-Coulomb joint
// strength, tau = c + sigma_n tan(phi) with tensile strength sigma_t, acting
// on the tributary area of face-face contact points. Contacts present when
// the run starts are bonded; a bond breaks irreversibly in tension or shear
// and the contact then carries friction only (the joint model the strength
// reduction work scales by a factor). Force law: joint_law.hpp.
#pragma once

#include "joint_law.hpp"
#include "talus/dda/contact_model.hpp"
#include "talus/params.hpp"

namespace talus::contact {

class MohrCoulomb final : public dda::ContactModel {
 public:
  static ParamSet describe();
  explicit MohrCoulomb(const ParamValues& v);

  double max_stiffness() const override;
  double damping_ratio() const override { return p_.damping_ratio; }
  std::uint8_t initial_state() const override;
  void compute(const dda::ContactBatch& batch, double dt) const override;
  const JointParameters& parameters() const { return p_; }

 private:
  JointParameters p_;
};

}  // namespace talus::contact
