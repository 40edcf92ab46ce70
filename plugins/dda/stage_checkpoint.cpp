// The dda stage's checkpoint state (DdaStage::save_state, load_state): its
// byte encoding through talus/state_archive.hpp, and the checks that a restored
// state fits this scene before any contact loop reads it.
#include "dda_stage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "talus/error.hpp"
#include "talus/state_archive.hpp"

namespace talus::dda {

namespace {

// ContactKey has padding: its fields go one by one so that equal states
// give equal bytes (restarts are compared bit for bit).
void archive_keys(StateWriter& w, const std::vector<ContactKey>& keys) {
  w.value<std::uint64_t>(keys.size());
  for (const auto& k : keys) {
    w.value(k.model);
    w.value(k.a);
    w.value(k.b);
    w.value(k.feature);
  }
}

void archive_keys(StateReader& r, std::vector<ContactKey>& keys) {
  std::uint64_t n = 0;
  r.value(n);
  if (n > r.in.size() / 20) r.truncated();
  keys.resize(n);
  for (auto& k : keys) {
    r.value(k.model);
    r.value(k.a);
    r.value(k.b);
    r.value(k.feature);
  }
}

template <class Archive, class Set>
void archive_contacts(Archive& a, Set& c) {
  archive_keys(a, c.key);
  a.vector(c.point);
  a.vector(c.normal);
  a.vector(c.velocity);
  a.vector(c.shear);
  a.vector(c.force);
  a.vector(c.gap);
  a.vector(c.area);
  a.vector(c.mass);
  a.vector(c.strain_energy);
  a.vector(c.dissipated);
  a.vector(c.state);
}

}  // namespace

std::string DdaStage::save_state() const {
  StateWriter w;
  w.value(static_cast<std::uint8_t>(started_));
  w.value(dt_stable_);
  w.value(slipping_);
  w.value(energy_ ? *energy_ : BlockEnergy{});
  w.vector(momentum_);
  archive_contacts(w, const_cast<ContactSet&>(contacts_));
  return std::move(w.out);
}

void DdaStage::load_state(std::string_view bytes) {
  StateReader r{bytes, "the dda stage's state"};
  std::uint8_t started = 0;
  r.value(started);
  started_ = started != 0;
  r.value(dt_stable_);
  r.value(slipping_);
  BlockEnergy energy;
  r.value(energy);
  if (energy_) *energy_ = energy;
  std::vector<Vec3> momentum;
  r.vector(momentum);
  if (momentum.size() != momentum_.size())
    throw InputError("error: checkpoint: it has " + std::to_string(momentum.size()) + " blocks, this scene " +
                     std::to_string(momentum_.size()));
  momentum_ = std::move(momentum);
  archive_contacts(r, contacts_);
  r.finish();
  check_restored(energy);
  if (mass_scaling_) {  // the inertia scales follow from the restored contacts alone
    std::fill(inertia_scale_.begin(), inertia_scale_.end(), 1.0);
    update_time_step();
  }
}

// A stage state that is intact but wrong must not reach the contact loops,
// which index blocks and models by the keys and rely on their order.
void DdaStage::check_restored(const BlockEnergy& energy) const {
  auto fail = [](const std::string& what) { throw InputError("error: checkpoint: the dda stage's state: " + what); };
  if (!(dt_stable_ > 0.0)) fail("stable time step " + std::to_string(dt_stable_) + " is not > 0");
  for (double e : {energy.kinetic, energy.potential, energy.strain, energy.dissipated, energy.external_work})
    if (!std::isfinite(e)) fail("a block energy is not finite");
  for (const Vec3& m : momentum_)
    if (!is_finite(m)) fail("a block's angular momentum is not finite");
  const ContactSet& c = contacts_;
  const std::size_t n = c.key.size();
  for (std::size_t size : {c.point.size(), c.normal.size(), c.velocity.size(), c.shear.size(), c.force.size(),
                           c.gap.size(), c.area.size(), c.mass.size(), c.strain_energy.size(), c.dissipated.size(),
                           c.state.size()})
    if (size != n)
      fail("its contact arrays disagree in length (" + std::to_string(size) + " and " + std::to_string(n) + " keys)");
  const std::size_t blocks = momentum_.size();
  for (std::size_t k = 0; k < n; ++k) {
    const ContactKey& key = c.key[k];
    const std::string contact = "contact " + std::to_string(k);
    if (key.model >= models_.size())
      fail(contact + " names contact model " + std::to_string(key.model) + "; the scene has " +
           std::to_string(models_.size()));
    if (key.a >= blocks || key.b >= blocks || key.a == key.b)
      fail(contact + " joins blocks " + std::to_string(key.a) + " and " + std::to_string(key.b) + "; the scene has " +
           std::to_string(blocks) + " blocks");
    if (k > 0 && key < c.key[k - 1]) fail(contact + " is out of order (contacts are sorted by model and blocks)");
    if (fixed_joints_ && (n != joint_key_.size() || !(key == joint_key_[k])))
      fail(contact + " is not one of the scene's fixed joints (\"joints\": \"initial_faces\" keeps the faces that "
                     "touch at the start)");
    if (!is_finite(c.point[k]) || !is_finite(c.normal[k]) || !is_finite(c.velocity[k]) || !is_finite(c.shear[k]) ||
        !is_finite(c.force[k]) || !std::isfinite(c.gap[k]) || !std::isfinite(c.area[k]) || !std::isfinite(c.mass[k]) ||
        !std::isfinite(c.strain_energy[k]) || !std::isfinite(c.dissipated[k]))
      fail(contact + " has a non-finite value");
  }
}

}  // namespace talus::dda
