// Contact models for the DDA stage (plugin kind "contact"). A model works on a
// structure-of-arrays batch of contact points (DESIGN.md principle 1): the
// stage makes one virtual call per model per step, the model runs a plain
// loop inside.
//
// Geometry convention: each contact point lies between blocks a and b; the
// unit normal points from a to b; gap < 0 is a penetration. The force a model
// returns acts on b at the point; a receives its opposite. The shear spring
// displacement and the state bits are the contact's history: the stage keeps
// them per block pair and geometric feature from step to step, and resets
// them when the contact is new.
//
// Springs are per contact point (classic DDA penalty springs, Shi 1988): a
// face-face contact with four manifold points is four springs. `area` is the
// tributary area of a point of a face-face contact (zero for vertex-face and
// edge-edge contacts) and is what cohesion and tensile strength act on.
#pragma once

#include <cstddef>
#include <cstdint>

#include "talus/plugin.hpp"
#include "talus/vec3.hpp"

namespace talus::dda {

// Contact state (low bits of ContactBatch::state).
enum ContactState : std::uint8_t {
  contact_open = 0,   // gap >= 0, no force (unless bonded)
  contact_stick = 1,  // closed, shear spring elastic
  contact_slip = 2,   // closed, sliding at the strength limit
};
inline constexpr std::uint8_t contact_state_mask = 0x3;
// Flag: a cohesive/tensile bond is intact (mohr_coulomb). Set on contacts that
// exist when the run starts; once cleared it never comes back.
inline constexpr std::uint8_t contact_bonded = 0x4;

struct ContactBatch {
  std::size_t size = 0;

  // Geometry and kinematics this step (read only).
  const double* gap = nullptr;       // signed normal distance, < 0 when penetrating, m
  const Vec3* normal = nullptr;      // unit normal from a to b
  const Vec3* velocity = nullptr;    // velocity of b's material point minus a's at the contact, m/s
  const double* area = nullptr;      // tributary area (face-face contacts), m^2
  const double* mass = nullptr;      // effective mass for damping (share of the pair's reduced mass), kg

  // History (read and written, persists between steps).
  Vec3* shear = nullptr;             // elastic shear spring elongation, tangent to the contact, m
  std::uint8_t* state = nullptr;     // ContactState | flags

  // Results (written for every contact).
  Vec3* force = nullptr;             // force on b, N
  double* strain_energy = nullptr;   // elastic energy stored in the springs now, J
  double* dissipated = nullptr;      // energy dissipated during this step (friction, damping), J
};

class TALUS_API ContactModel : public Model {
 public:
  ~ContactModel() override;

  // Largest spring stiffness of one contact point, N/m (stable time step).
  virtual double max_stiffness() const = 0;
  // Damping ratio of the contact springs (stable time step).
  virtual double damping_ratio() const { return 0.0; }
  // State bits of a contact present when the run starts (e.g. bonded joints).
  virtual std::uint8_t initial_state() const { return contact_open; }
  // Forces over a step of length dt for every contact of the batch.
  virtual void compute(const ContactBatch& batch, double dt) const = 0;
};

}  // namespace talus::dda
