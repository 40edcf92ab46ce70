// Fixed joints ("joints": "initial_faces"): the rigid-block-spring method
// (Kawai 1978) on the DDA's blocks. A tessellated slope's blocks share faces;
// with contacts sought at every step, blocks that share only an edge or a
// vertex get contacts whose normal is any plane through it, and the kinks of
// a stepped slip surface lock it. Here the joints are the face-face contact
// points that touch at the start, each kept as one material point of either
// block and a's face normal, so the springs see the relative displacement of
// the two blocks on a fixed joint plane that turns with a.

#include "dda_stage.hpp"

namespace talus::dda {
namespace {

// Largest gap, as a fraction of the contact margin, at which faces count as
// sharing a joint (the same tolerance as a bond at the start).
constexpr double joint_gap = 0.01;

}  // namespace

void DdaStage::fix_joints(const BlockSet& b) {
  std::vector<std::uint8_t> keep(contacts_.size(), 0);
  for (std::size_t c = 0; c < contacts_.size(); ++c)
    keep[c] = contacts_.area[c] > 0.0 && contacts_.gap[c] <= joint_gap * margin_;
  contacts_.keep(keep);
  const std::size_t n = contacts_.size();
  joint_on_a_.resize(n);
  joint_on_b_.resize(n);
  joint_normal_.resize(n);
  joint_gap_.resize(n);
  joint_manifold_.resize(n);
  joint_key_ = contacts_.key;
  for (std::size_t c = 0; c < n; ++c) {
    const ContactKey& k = contacts_.key[c];
    const Vec3 p = contacts_.point[c];
    joint_on_a_[c] = rotate_inverse(b.orientation[k.a], p - b.position[k.a]);
    joint_on_b_[c] = rotate_inverse(b.orientation[k.b], p - b.position[k.b]);
    joint_normal_[c] = rotate_inverse(b.orientation[k.a], contacts_.normal[c]);
    joint_gap_[c] = contacts_.gap[c];
    joint_manifold_[c] = 1.0 / (contacts_.mass[c] * inverse_mass_sum(k.a, k.b));
  }
}

void DdaStage::place_fixed_joints(const BlockSet& b) {
  const std::size_t n = contacts_.size();
#pragma omp parallel for schedule(static) if (n > 8192)
  for (std::size_t c = 0; c < n; ++c) {
    const ContactKey& k = contacts_.key[c];
    const Vec3 on_a = b.to_world(k.a, joint_on_a_[c]);
    const Vec3 on_b = b.to_world(k.b, joint_on_b_[c]);
    const Vec3 normal = rotate(b.orientation[k.a], joint_normal_[c]);
    contacts_.point[c] = 0.5 * (on_a + on_b);
    contacts_.normal[c] = normal;
    contacts_.gap[c] = joint_gap_[c] + dot(on_b - on_a, normal);
    contacts_.velocity[c] = b.velocity_at(k.b, on_b) - b.velocity_at(k.a, on_a);
    contacts_.mass[c] = 1.0 / (inverse_mass_sum(k.a, k.b) * joint_manifold_[c]);  // the inertia scales change
  }
}

}  // namespace talus::dda
