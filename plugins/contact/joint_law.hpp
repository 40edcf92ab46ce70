// The force law shared by the contact models: penalty springs with Coulomb
// friction (Shi 1988, DDA contact springs; seed sph-dda-rock-fluid-3d §2),
// viscous contact damping, and an optional cohesive/tensile bond
// (Mohr-Coulomb joint) that breaks irreversibly.
//
// Per contact point, with pen = -gap, v_n = v.n, v_t = v - v_n n:
//   normal  F_n = k_n pen - c_n v_n,  c_n = 2 xi sqrt(k_n m)      (>= 0 unless bonded)
//   shear   u_s <- rotate u_s into the tangent plane, u_s += v_t dt
//           F_s = -k_s u_s - c_s v_t while |k_s u_s| <= F_n tan(phi) + c A   (stick)
//           else |F_s| = F_n tan(phi) + c A along -u_s, u_s pulled back   (slip)
//   bond    breaks when k_n pen < -sigma_t A (tension), and when the shear
//           limit is reached if the joint is brittle; afterwards
//           c = sigma_t = 0 for that contact. A joint without shear softening
//           keeps c while it slips (perfectly plastic Mohr-Coulomb).
// The force acts on block b; energies: elastic energy in the springs, and the
// dissipated work of slip and damping over the step.
#pragma once

#include <algorithm>
#include <cmath>

#include "talus/dda/contact_model.hpp"

namespace talus::contact {

struct JointParameters {
  double normal_stiffness = 0.0;  // N/m
  double shear_stiffness = 0.0;   // N/m
  double tan_friction = 0.0;
  double damping_ratio = 0.0;
  double cohesion = 0.0;          // Pa
  double tensile_strength = 0.0;  // Pa
  bool brittle = true;            // the bond breaks at the first shear slip
};

// Largest spring stiffness of one contact point (the stable step).
inline double max_stiffness(const JointParameters& p) { return std::max(p.normal_stiffness, p.shear_stiffness); }

// A contact present at the start is bonded when the joint has any strength
// besides friction.
inline std::uint8_t initial_state(const JointParameters& p) {
  const bool bonded = p.cohesion > 0.0 || p.tensile_strength > 0.0;
  return bonded ? dda::contact_bonded : static_cast<std::uint8_t>(dda::contact_open);
}

inline void joint_law(const JointParameters& p, const dda::ContactBatch& b, double dt) {
  using namespace talus::dda;
  const double kn = p.normal_stiffness, ks = p.shear_stiffness;
  for (std::size_t c = 0; c < b.size; ++c) {
    const Vec3 n = b.normal[c];
    const Vec3 v = b.velocity[c];
    const double vn = dot(v, n);
    const Vec3 vt = v - vn * n;
    const double gap = b.gap[c];
    bool bonded = (b.state[c] & contact_bonded) != 0;
    const double area = b.area[c];

    if (bonded && -kn * gap < -p.tensile_strength * area) bonded = false;  // tensile failure
    if (gap >= 0.0 && !bonded) {
      b.shear[c] = {};
      b.state[c] = contact_open;
      b.force[c] = {};
      b.strain_energy[c] = 0.0;
      b.dissipated[c] = 0.0;
      continue;
    }

    const double m = b.mass[c];
    const double cn = 2.0 * p.damping_ratio * std::sqrt(kn * m);
    const double cs = 2.0 * p.damping_ratio * std::sqrt(ks * m);
    const double spring_n = -kn * gap;
    double fn = spring_n - cn * vn;
    if (!bonded) fn = std::max(fn, 0.0);
    // Work of the damping force over the step at the mid-step velocity
    // v(t) ~ v(t - dt/2) + F dt / 2m: consistent with the leapfrog's kinetic
    // energy even when the damping changes the velocity much in one step.
    const double vn_mid = vn + 0.5 * fn * dt / m;
    double dissipated = -(fn - spring_n) * vn_mid * dt;

    // Shear spring: carry the old elongation into the current tangent plane.
    Vec3 us = b.shear[c];
    const double old_len = norm(us);
    us -= dot(us, n) * n;
    const double len = norm(us);
    if (len > 0.0) us = us * (old_len / len);
    us += vt * dt;

    double limit = std::max(fn, 0.0) * p.tan_friction + (bonded ? p.cohesion * area : 0.0);
    double trial = ks * norm(us);
    if (bonded && p.brittle && trial > limit) {  // shear failure of the bond
      bonded = false;
      limit = std::max(fn, 0.0) * p.tan_friction;
    }
    Vec3 fs;
    std::uint8_t state;
    if (trial > limit) {
      const double us_len = norm(us);
      const Vec3 dir = us / us_len;
      const double kept = limit / ks;
      fs = -limit * dir;
      dissipated += limit * (us_len - kept);
      us = kept * dir;
      state = contact_slip;
    } else {
      fs = -ks * us - cs * vt;
      dissipated += cs * dot(vt, vt + (0.5 * dt / m) * fs) * dt;
      state = contact_stick;
    }
    b.shear[c] = us;
    b.state[c] = static_cast<std::uint8_t>(state | (bonded ? contact_bonded : 0));
    b.force[c] = fn * n + fs;
    b.strain_energy[c] = 0.5 * kn * gap * gap + 0.5 * ks * dot(us, us);
    b.dissipated[c] = dissipated;
  }
}

}  // namespace talus::contact
