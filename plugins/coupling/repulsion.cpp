#include "repulsion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <omp.h>

#include "talus/blocks.hpp"
#include "talus/eos.hpp"
#include "talus/error.hpp"
#include "talus/periodic.hpp"
#include "talus/world.hpp"

namespace talus::coupling {

ParamSet Repulsion::describe() {
  ParamSet p{"block_repulsion", "penalty repulsion F = max(0, Ks d - (v.n) Kd) n between the fluid and a DDA block's faces "
                          "(rock-fluid seed eq. 22); the block receives the reaction"};
  p.real("stiffness").unit("N/m").greater_than(0.0).optional()
      .doc("penalty stiffness K_s per fluid particle (default m c0^2 / r0^2: a particle at the sound speed stops "
           "within r0)");
  p.real("damping").unit("N s/m").min(0.0).optional()
      .doc("damping coefficient K_d of the approach velocity (default: half of critical, sqrt(K_s m))");
  p.real("distance").unit("m").greater_than(0.0).optional()
      .doc("thickness r0 of the repulsive layer outside the faces (default: the fluid's dp)");
  p.string("material").optional().doc("fluid material for the default stiffness (default: the only fluid material)");
  return p;
}

Repulsion::Repulsion(const ParamValues& v) {
  if (v.has("stiffness")) ks_param_ = v.real("stiffness");
  if (v.has("damping")) kd_param_ = v.real("damping");
  if (v.has("distance")) r0_param_ = v.real("distance");
  if (v.has("material")) material_name_ = v.string("material");
}

void Repulsion::setup(World& world, std::span<const int> bodies) {
  for (int bi : bodies) {
    bodies_.push_back(bi);
    names_.push_back(world.bodies[bi].name);
  }
}

void Repulsion::bind(World& world, const sph::FluidSettings&) {
  blocks_ = find_blocks(world, bodies_, "block_repulsion");
  const int material = coupling_material(world, bodies_.front(), "block_repulsion", material_name_);
  const Material& mat = world.materials[material];
  r0_ = r0_param_ > 0.0 ? r0_param_ : world.dp;
  period_ = periods(world);
  const double m_ref = mat.density * std::pow(world.dp, world.dim);
  const double c0 = mat.eos ? mat.eos->reference_sound_speed() : 0.0;
  if (ks_param_ <= 0.0 && !(c0 > 0.0))
    world.bodies[bodies_.front()].params.fail("boundary", "block_repulsion: give \"stiffness\" (material '" + mat.name +
                                                              "' has no EOS for the default)");
  spring_.stiffness = ks_param_ > 0.0 ? ks_param_ : m_ref * c0 * c0 / (r0_ * r0_);
  spring_.damping = kd_param_ >= 0.0 ? kd_param_ : std::sqrt(spring_.stiffness * m_ref);
  clear_fluid_inside(world, blocks_, 0.5 * world.dp * (1.0 - 1e-6));
  const auto mass = world.fluid.scalar("mass");
  min_mass_ = mass.empty() ? m_ref : *std::min_element(mass.begin(), mass.end());
  thread_force_.assign(omp_get_max_threads(), Vec3{});
  thread_torque_.assign(omp_get_max_threads(), Vec3{});
  ledger_.reset(blocks_.size());
}

// The penalty needs nothing beyond each fluid particle's own place; the
// reaction is summed over the ranks (ImpulseLedger).
std::string Repulsion::why_not_on_ranks() const { return {}; }

double Repulsion::stable_time_step(const World&) const { return spring_.stable_time_step(min_mass_); }

std::uint64_t Repulsion::add_direct_forces(World& world, const sph::FluidView& fluid, const sph::FluidRates& rates) {
  const BlockSet& b = *world.blocks;
  const std::int64_t n = static_cast<std::int64_t>(fluid.position.size());
  // Halo rows (other ranks' particles) get rates too, but their owners give the block their reaction.
  const std::int64_t owned = static_cast<std::int64_t>(world.fluid.owned_size());
  const double r0 = r0_;
  const sph::PenaltySpring spring = spring_;
  std::uint64_t pairs = 0;
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const std::size_t blk = blocks_[k];
    const Polyhedron& poly = b.shape[blk];
    const Quaternion q = b.orientation[blk];
    const Vec3 X = b.position[blk], V = b.velocity[blk], w = b.angular_velocity[blk];
    normals_.resize(poly.normals.size());
    offsets_.resize(poly.normals.size());
    for (std::size_t f = 0; f < poly.normals.size(); ++f) {
      normals_[f] = rotate(q, poly.normals[f]);
      offsets_[f] = poly.offsets[f] + dot(normals_[f], X);
    }
    const Vec3* nrm = normals_.data();
    const double* off = offsets_.data();
    const std::size_t faces = normals_.size();
    const Vec3 period = period_;
    const Vec3 lo = b.bounds_lo[blk] - Vec3{r0, r0, r0}, hi = b.bounds_hi[blk] + Vec3{r0, r0, r0};
#pragma omp parallel reduction(+ : pairs)
    {
      Vec3 force{}, torque{};
#pragma omp for schedule(static)
      for (std::int64_t ii = 0; ii < n; ++ii) {
        const Vec3 x = X + minimum_image(fluid.position[ii] - X, period);  // the image near the block
        if (x.x < lo.x || x.y < lo.y || x.z < lo.z || x.x > hi.x || x.y > hi.y || x.z > hi.z) continue;
        double s = -std::numeric_limits<double>::infinity();
        std::size_t face = 0;
        for (std::size_t f = 0; f < faces; ++f) {
          const double d = dot(nrm[f], x) - off[f];
          if (d > s) {
            s = d;
            face = f;
          }
        }
        if (s >= r0) continue;
        ++pairs;
        const Vec3 nf = nrm[face];
        const Vec3 v_rel = fluid.velocity[ii] - (V + cross(w, x - X));
        const double fn = spring.normal_force(r0 - s, dot(v_rel, nf));
        if (fn <= 0.0) continue;
        const Vec3 on_fluid = nf * fn;
        rates.acceleration[ii] += on_fluid / fluid.mass[ii];
        if (ii >= owned) continue;
        force -= on_fluid;
        torque -= cross(x - X, on_fluid);
      }
      thread_force_[omp_get_thread_num()] = force;
      thread_torque_[omp_get_thread_num()] = torque;
    }
    Vec3 force{}, torque{};
    for (std::size_t t = 0; t < thread_force_.size(); ++t) {
      force += thread_force_[t];
      torque += thread_torque_[t];
      thread_force_[t] = thread_torque_[t] = Vec3{};
    }
    ledger_.set(k, force, torque);
  }
  return pairs;
}

void Repulsion::describe_passes(StagePlan& plan) const {
  std::string names;
  for (const auto& n : names_) names += (names.empty() ? "'" : ", '") + n + "'";
  plan.passes.push_back("fluid-block pass (block_repulsion " + names + "): penalty force (Ks d - (v.n) Kd) n on the fluid "
                        "within r0 of the faces; reaction on the block");
}

}  // namespace talus::coupling
