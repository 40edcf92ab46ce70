// The joint law of a block's contact model with its strength divided by the
// trial factor F: c/F, tan(phi)/F and sigma_t/F (the tensile strength is
// reduced with the cohesion). Built from the body's own "contact" entry
// (penalty_coulomb or mohr_coulomb), so the scene states each joint once.
#pragma once

#include <string>

#include "joint_law.hpp"
#include "talus/dda/contact_model.hpp"
#include "talus/params.hpp"

namespace talus::strength_reduction {

class ReducedJoint final : public dda::ContactModel {
 public:
  // `model`: the contact type; `v`: its validated parameters. Throws
  // InputError through `body` for a model whose strength cannot be reduced.
  ReducedJoint(const std::string& model, const ParamValues& v, const ParamValues& body);

  // Strengths divided by `factor`. `unbreakable`: a bond holds any tension
  // too (the gravity-loaded state, where no joint may open: with a tensile
  // strength of zero, a contact that starts a rounding error apart would
  // otherwise lose its cohesion before the springs take up the weight).
  void set_factor(double factor, bool unbreakable = false);
  double factor() const { return factor_; }
  const contact::JointParameters& base() const { return base_; }

  double max_stiffness() const override;
  double damping_ratio() const override { return base_.damping_ratio; }
  std::uint8_t initial_state() const override;
  void compute(const dda::ContactBatch& batch, double dt) const override;

 private:
  contact::JointParameters base_, reduced_;
  double factor_ = 1.0;
};

}  // namespace talus::strength_reduction
