// The fluid-wall passes of the wcsph stage. Wall models supply wall sets
// (sph/boundary_pass.hpp); the stage runs, for every set, one pass in which
// each fluid particle gathers the set's wall particles with the fluid-fluid
// terms less density diffusion: pressure, the scene's viscous term (as seen
// against a wall, viscosity_term.hpp) and continuity. A rigid body's set also
// sums the reaction on the body in the same traversal.
//
// Reaction: the force on i from the body is m_i a_i(body); the body gets
// -m_i a_i. Its torque about the centroid X sums (x_b - X) x (-m_i a_ib) over
// pairs = (x_i - X) x (-m_i a_i) + m_i sum_b dx_ib x a_ib (dx = x_i - x_b), so
// non-central (viscous) pair forces contribute their exact moment
// (sph::WithPairMoment). A body may straddle a periodic boundary (the dda stage
// does not wrap blocks), so x_i - X is taken as its minimum image, for the lever
// arm and for the bounding-box filter alike.
#include <algorithm>

#include <omp.h>

#include "fluid_fields.hpp"
#include "fluid_sums.hpp"
#include "talus/periodic.hpp"
#include "talus/sph/pair_loop.hpp"
#include "talus/world.hpp"
#include "viscosity_term.hpp"
#include "wcsph_stage.hpp"

namespace talus::wcsph {

namespace {

constexpr std::size_t thread_stride = 8;  // doubles per cache line: no two threads write to one line

struct BodyReaction {
  Vec3 force, torque;
  BodyReaction& operator+=(const BodyReaction& o) {
    force += o.force;
    torque += o.torque;
    return *this;
  }
};

// Real: the type the fluid is kept in (double, or float in mixed precision).
template <class Real>
struct WallPass {
  const sph::FluidView& fluid;
  sph::NeighbourFields<Real> own;   // the fluid's fields, as the i-state of the pass
  sph::FluidReactions<Real> rates;  // the fluid's acceleration and density rate
  double* visc_max_by_thread;  // a cache line per thread: the largest s.visc its particles had
  const sph::WallSet& set;
  const KernelTable& kernel;
  const double* material_mu;  // where the fluid has no mu_eff
  bool continuity;
  Vec3 period;
  // The fluid's own rows: the outer loops stop there, as the halo rows' rates
  // are not wanted (their values come from their owners) and their reaction
  // on a body is their owner's.
  std::size_t owned;

  template <class S>
  S start(Index i) const {
    S s;
    s.v = own.velocity[i];
    s.rho = own.density[i];
    s.inv_rho = 1.0 / s.rho;
    s.p = own.pressure[i];
    s.c = own.sound_speed[i];
    s.mu = fluid.viscosity.empty() ? material_mu[fluid.material[i]] : fluid.viscosity[i];
    return s;
  }
  void add_rates(Index i, const FluidSums& s) const {
    rates.acc[i] = Vec3(rates.acc[i]) + s.acc;
    if (continuity) rates.drho[i] += s.drho;
    double& visc_max = visc_max_by_thread[thread_stride * omp_get_thread_num()];
    visc_max = std::max(visc_max, s.visc);
  }

  template <class... Terms>
  std::uint64_t against_walls(const Terms&... terms) const {
    auto first = [&](Index i) { return start<FluidSums>(i); };
    auto finish = [&](Index i, const FluidSums& s) { add_rates(i, s); };
    return sph::pair_pass(owned, fluid.position, *set.cells, kernel, sph::other_set, first, finish, terms...);
  }

  template <class... Terms>
  BodyReaction against_body(std::uint64_t& pairs, const Terms&... terms) const {
    const double radius = kernel.support_radius();
    const Vec3 pad{radius, radius, radius};
    const Vec3 lo = set.body.lo - pad, hi = set.body.hi + pad, centre = set.body.centre;
    auto arm_of = [&](Index i) { return minimum_image(fluid.position[i] - centre, period); };  // lever arm
    auto skip = [&](Index i) {
      const Vec3 xi = centre + arm_of(i);  // the image near the body
      return xi.x < lo.x || xi.y < lo.y || xi.z < lo.z || xi.x > hi.x || xi.y > hi.y || xi.z > hi.z;
    };
    auto first = [&](Index i) { return start<BodySums>(i); };
    auto finish = [&](Index i, const BodySums& s, BodyReaction& on_body) {
      add_rates(i, s);
      const double mi = own.mass[i];
      const Vec3 force = s.acc * (-mi);
      on_body.force += force;
      on_body.torque += cross(arm_of(i), force) + s.moment * mi;
    };
    return sph::reducing_pair_pass<BodyReaction>(owned, fluid.position, *set.cells, kernel,
                                                 sph::other_set, pairs, skip, first, finish,
                                                 sph::with_pair_moment(terms...));
  }
};

}  // namespace

sph::FluidView WcsphStage::fluid_view(World& world) const {
  ParticleStore& s = world.fluid;
  sph::FluidView fluid{&cells_, s.position()};
  fluid.material = s.material();
  if (per_particle_viscosity_) fluid.viscosity = s.scalar("mu_eff");
  if (fluid_in_float(s)) {
    const FluidFieldsOf<float> f(s);
    fluid.single = f.neighbours();
    fluid.single.inv_density = reciprocals<float>().data();
    return fluid;
  }
  const FluidFields f(s);
  fluid.velocity = f.v;
  fluid.density = f.rho;
  fluid.pressure = f.p;
  fluid.sound_speed = f.c;
  fluid.mass = f.m;
  fluid.inv_density = reciprocals<double>();
  return fluid;
}

sph::FluidRates WcsphStage::fluid_rates(World& world) {
  ParticleStore& s = world.fluid;
  sph::FluidRates rates{{}, {}, &rates_visc_max_};
  if (fluid_in_float(s)) {
    rates.acceleration_single = s.vector_f32("acceleration");
    rates.density_rate_single = s.scalar_f32("density_rate");
  } else {
    rates.acceleration = s.vector("acceleration");
    rates.density_rate = s.scalar("density_rate");
  }
  return rates;
}

std::uint64_t WcsphStage::wall_passes(World& world) {
  const sph::FluidView fluid = fluid_view(world);
  const sph::FluidRates rates = fluid_rates(world);
  visc_max_by_thread_.assign(thread_stride * omp_get_max_threads(), 0.0);
  const ViscositySettings viscosity = viscosity_settings(world);
  const bool continuity = density_ == DensityMode::continuity;
  std::uint64_t pairs = 0;
  for (sph::SphBoundary* wall : walls_) {
    pairs += wall->fill_wall_state(world, fluid);
    const std::span<const sph::WallSet> sets = wall->wall_sets();
    // The fluid and each wall set in the types they are kept in (one instantiation per pair of types).
    for (std::size_t k = 0; k < sets.size(); ++k) with_fluid_fields(world.fluid, [&](auto f) {
      using Real = typename decltype(f.rho)::value_type;
      const sph::WallSet& set = sets[k];
      const WallPass<Real> pass{fluid,      f.neighbours(), {f.a.data(), f.drho.data()}, visc_max_by_thread_.data(),
                                set,        world.kernel,   material_mu_.data(),         continuity,
                                period_,    world.fluid.owned_size()};
      set.visit_fields([&](const auto& walls, const auto* viscous_velocity) {
        auto viscous_nb = walls;
        viscous_nb.velocity = viscous_velocity;
        const sph::PressureForce pressure{walls};
        const sph::Continuity cont{walls};  // its rate is added only with continuity density
        pairs += with_viscosity_term<Neighbour::wall>(viscosity, walls, viscous_nb, [&](const auto& viscous) {
          if (!set.rigid_body) return pass.against_walls(pressure, viscous, cont);
          std::uint64_t body_pairs = 0;
          const BodyReaction reaction = pass.against_body(body_pairs, pressure, viscous, cont);
          wall->take_reaction(world, k, reaction.force, reaction.torque);
          return body_pairs;
        });
      });
    });
    pairs += wall->add_direct_forces(world, fluid, rates);
  }
  for (std::size_t t = 0; t < visc_max_by_thread_.size(); t += thread_stride)
    rates_visc_max_ = std::max(rates_visc_max_, visc_max_by_thread_[t]);
  return pairs;
}

std::uint64_t WcsphStage::wall_density_passes(World& world) {
  const std::span<const Vec3> x = world.fluid.position();
  std::uint64_t pairs = 0;
  for (sph::SphBoundary* wall : walls_) {
    wall->refresh_wall_sets(world);
    for (const sph::WallSet& set : wall->wall_sets())
      world.fluid.visit_scalar("density", [&](auto rho) {
        set.visit_fields([&](const auto& walls, const auto*) {
          auto start = [](Index) { return sph::DensitySums{}; };
          auto finish = [&](Index i, const sph::DensitySums& sum) { rho[i] += sum.rho_sum; };
          pairs += sph::pair_pass(world.fluid.owned_size(), x, *set.cells, world.kernel, sph::other_set, start,
                                  finish, sph::DensitySum{walls.mass});
        });
      });
  }
  return pairs;
}

}  // namespace talus::wcsph
