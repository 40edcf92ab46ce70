// penalty_coulomb: DDA contact springs (normal and shear penalty springs,
// Shi 1988) with Coulomb friction and viscous contact damping; states
// open / stick / slip. Seed sph-dda-rock-fluid-3d §2 (explicit DDA with
// penalty contacts). Force law: joint_law.hpp.
#pragma once

#include "joint_law.hpp"
#include "talus/dda/contact_model.hpp"
#include "talus/params.hpp"

namespace talus::contact {

// Declares the parameters shared with mohr_coulomb.
void declare_springs(ParamSet& p);
JointParameters read_springs(const ParamValues& v);

class PenaltyCoulomb final : public dda::ContactModel {
 public:
  static ParamSet describe();
  explicit PenaltyCoulomb(const ParamValues& v);

  double max_stiffness() const override;
  double damping_ratio() const override { return p_.damping_ratio; }
  void compute(const dda::ContactBatch& batch, double dt) const override;
  const JointParameters& parameters() const { return p_; }

 private:
  JointParameters p_;
};

}  // namespace talus::contact
