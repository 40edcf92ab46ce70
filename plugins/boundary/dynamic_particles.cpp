#include "dynamic_particles.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <omp.h>

#include "talus/eos.hpp"
#include "talus/error.hpp"
#include "talus/geometry.hpp"
#include "talus/parallel.hpp"
#include "talus/periodic.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/sph/pair_loop.hpp"
#include "talus/sph/wall_fields.hpp"
#include "talus/world.hpp"

namespace talus::boundary {

namespace {

using sph::wall_velocity;
using sph::wall_density;
using sph::wall_pressure;
using sph::wall_mass;
using sph::wall_sound_speed;
using sph::wall_density_rate;
using sph::wall_density_n;
using sph::wall_viscous_velocity;

// Where the particles of a moving wall started: its motion maps them from
// there. Only models with a moving wall keep it; still walls never leave it.
const FieldInfo wall_position0{"position0", FieldType::vector, "m", false, true};
std::span<Vec3> start_positions(ParticleStore& s, std::size_t first, std::size_t count) {
  return s.vector("position0").subspan(first, count);
}

// The wall fields that go to float together: in a scene of mixed precision,
// with DBC walls (mDBC's ghost-node solve writes double), unless another
// model that shares the wall store requires them in double.
const FieldInfo* const wall_fields_in_float[] = {&wall_velocity,     &wall_density,      &wall_pressure,
                                                 &wall_mass,         &wall_sound_speed,  &wall_density_rate,
                                                 &wall_density_n};

// The seven in one type; with the mirrored viscous velocity, eight.
void keep_wall_fields_alike(ParticleStore& s) {
  std::size_t in_float = 0, fields = std::size(wall_fields_in_float);
  auto count = [&](const FieldInfo& f) { in_float += is_single(s.info(f.name).type); };
  for (const FieldInfo* f : wall_fields_in_float) count(*f);
  if (s.has(wall_viscous_velocity.name)) {
    count(wall_viscous_velocity);
    ++fields;
  }
  if (in_float == 0 || in_float == fields) return;
  for (const FieldInfo* f : wall_fields_in_float) s.require(*f);
  if (s.has(wall_viscous_velocity.name)) s.require(wall_viscous_velocity);
}

bool walls_in_float(const ParticleStore& s) { return s.info(wall_density.name).type == FieldType::scalar_f32; }

// The wall store's fields over this model's particles [first, first + count),
// all but the position in Real (double, or float in mixed precision).
template <class Real>
struct WallFieldsOf {
  std::span<Vec3> x;
  std::span<VectorOf<Real>> v;
  std::span<Real> rho, p, c, m, drho, rho_n;
  std::span<std::int32_t> mat, body;
  WallFieldsOf(ParticleStore& s, std::size_t first, std::size_t count)
      : x(s.position().subspan(first, count)),
        v(s.column<VectorOf<Real>>("velocity").subspan(first, count)),
        rho(s.column<Real>("density").subspan(first, count)),
        p(s.column<Real>("pressure").subspan(first, count)),
        c(s.column<Real>("sound_speed").subspan(first, count)),
        m(s.column<Real>("mass").subspan(first, count)),
        drho(s.column<Real>("density_rate").subspan(first, count)),
        rho_n(s.column<Real>("density_n").subspan(first, count)),
        mat(s.material().subspan(first, count)),
        body(s.body().subspan(first, count)) {}
  sph::NeighbourFields<Real> neighbours() const {
    return {v.data(), rho.data(), p.data(), c.data(), m.data(), mat.data()};
  }
};

// f(WallFieldsOf<float>) or f(WallFieldsOf<double>), as the store keeps them.
template <class F>
decltype(auto) with_wall_fields(ParticleStore& s, std::size_t first, std::size_t count, F&& f) {
  if (walls_in_float(s)) return f(WallFieldsOf<float>(s, first, count));
  return f(WallFieldsOf<double>(s, first, count));
}

// The wall material: the body's "material", else the only fluid material.
int wall_material(const World& world, const Body& body) {
  if (body.material >= 0) return body.material;
  std::set<int> fluid_materials;
  for (const Body& b : world.bodies)
    if (b.kind == BodyKind::fluid && b.material >= 0) fluid_materials.insert(b.material);
  if (fluid_materials.size() == 1) return *fluid_materials.begin();
  body.params.fail("material", "wall '" + body.name + "' with dynamic_particles needs a \"material\" (its reference "
                               "density and EOS) when the scene has " +
                                   std::to_string(fluid_materials.size()) + " fluid materials");
}

// Shepard interpolation of the fluid velocity at a wall particle b (i = b, j = f):
// v~_b = sum_f v_f W_bf / sum_f W_bf (Adami et al. 2012, eq. 22).
// V: the fluid velocity's stored type (Vec3, or Vec3f in mixed precision).
template <class V>
struct VelocityShepard {
  static constexpr bool uses_value = true, uses_gradient = false;
  const V* velocity = nullptr;
  template <class S>
  void pair(const sph::Pair& q, S& s) const {
    s.wsum += q.w;
    s.vsum += Vec3(velocity[q.j]) * q.w;
  }
};

// What a wall particle sums over its fluid neighbours.
struct WallSums {
  Vec3 v;             // v_b, the wall's own velocity (continuity)
  double rho = 0.0;   // rho_b (continuity)
  double drho = 0.0;  // continuity
  double wsum = 0.0;  // Shepard weights
  Vec3 vsum;          // Shepard-weighted fluid velocity
};

}  // namespace

ParamSet DynamicParticles::describe() {
  ParamSet p{"dynamic_particles",
             "dynamic boundary particles (DBC, Crespo et al. 2007, as DualSPHysics): wall particles with density "
             "from continuity and pressure from the wall material's EOS"};
  p.choice("no_slip", {"extrapolated", "wall_velocity"})
      .default_value("extrapolated")
      .doc("wall velocity in the laminar/Laplacian viscous term: extrapolated = 2 v_wall - Shepard(v_fluid) (Adami et "
           "al. 2012; no-slip on the wall surface, second order), wall_velocity = the wall particle's own (DualSPHysics "
           "DBC; no-slip ~0.7 dp behind the surface, first order). Artificial viscosity always uses the wall's own");
  p.choice("method", {"dbc", "mdbc"})
      .default_value("dbc")
      .doc("how the wall particles get their density: dbc = continuity with the fluid (Crespo et al. 2007), mdbc = "
           "extrapolated from a ghost node mirrored across the wall surface (English et al. 2022: no DBC gap, the "
           "wall pressure continues the fluid's)");
  p.choice("slip", {"no_slip", "free_slip"})
      .default_value("no_slip")
      .doc("free_slip (needs method mdbc): the viscous terms, artificial viscosity included, see the ghost node's "
           "tangential velocity and its mirrored normal velocity, so the wall stops flow through it but exerts no "
           "shear (a symmetry plane); no_slip: as \"no_slip\" says");
  return p;
}

DynamicParticles::DynamicParticles(const ParamValues& v)
    // Validated values always hold the choices (they have defaults); tests may pass none.
    : no_slip_(v.has("no_slip") && v.string("no_slip") == "wall_velocity" ? NoSlip::wall_velocity
                                                                          : NoSlip::extrapolated),
      method_(v.has("method") && v.string("method") == "mdbc" ? Method::mdbc : Method::dbc),
      slip_(v.has("slip") && v.string("slip") == "free_slip" ? sph::WallSlip::free_slip : sph::WallSlip::no_slip) {
  if (slip_ == sph::WallSlip::free_slip && method_ != Method::mdbc)
    v.fail("slip", "free_slip needs \"method\": \"mdbc\": DBC wall particles have no wall normal to mirror the "
                   "fluid velocity about");
}

void DynamicParticles::setup(World& world, std::span<const int> bodies) {
  ParticleStore& s = world.boundary;
  for (const FieldInfo* f : wall_fields_in_float) {
    FieldInfo field = *f;
    field.single_when_mixed = method_ == Method::dbc;
    s.require(field);
  }
  keep_wall_fields_alike(s);
  if (count_ > 0 && first_ + count_ != s.size())
    throw RunError("dynamic_particles: setup called again after other wall particles were added");
  if (count_ == 0) first_ = s.size();
  slot_of_body_.assign(world.bodies.size(), -1);
  for (std::size_t k = 0; k < bodies_.size(); ++k) slot_of_body_[bodies_[k]] = static_cast<int>(k);

  const double radius = world.kernel.h() > 0 ? world.kernel.support_radius() : 0.0;
  for (int bi : bodies) {
    const Body& body = world.bodies[bi];
    const ParamValues& v = body.params;
    const double dp = body.dp > 0 ? body.dp : world.dp;
    if (!(dp > 0)) v.fail("dp", "wall '" + body.name + "' needs a particle spacing \"dp\"");
    // Default: enough layers to fill the kernel support behind the wall surface.
    const int layers = v.has("layers") ? static_cast<int>(v.integer("layers"))
                                       : std::max(1, static_cast<int>(std::ceil(radius / dp - 1e-9)));
    const int material = wall_material(world, body);
    if (!world.materials[material].eos)
      v.fail("material", "wall '" + body.name + "': material '" + world.materials[material].name +
                             "' has no \"eos\"; dynamic_particles needs one for the wall pressure");
    const std::vector<Vec3> points = wall_points(v.alternative("shape"), v.alternative_values("shape"), dp, world.dim,
                                                 layers, world.lo, world.hi);
    if (points.empty()) v.fail("shape", "wall '" + body.name + "' has no wall particle at dp = " + std::to_string(dp));
    const std::size_t first = s.append(points.size());
    const double rho0 = world.materials[material].density;
    const double mass = rho0 * lattice_volume(v.alternative("shape"), v.alternative_values("shape"), dp, world.dim);
    if (const std::string adjusted = lattice_adjustment(v.alternative("shape"), v.alternative_values("shape"), dp,
                                                        world.dim);
        !adjusted.empty())
      world.warnings.add("wall '" + body.name + "' (" + v.pointer("shape") + "): " + adjusted);
    with_wall_fields(s, first, points.size(), [&](auto w) {
      for (std::size_t k = 0; k < points.size(); ++k) {
        w.x[k] = points[k];
        w.rho[k] = rho0;
        w.m[k] = mass;
        w.mat[k] = material;
        w.body[k] = bi;
      }
    });
    const auto surface = wall_surface(v.alternative("shape"), v.alternative_values("shape"), world.dim, world.lo,
                                      world.hi);
    slot_of_body_[bi] = static_cast<int>(bodies_.size());
    bodies_.push_back(bi);
    body_names_.push_back(body.name);
    motion_.push_back(v.has("motion") ? PrescribedMotion(v.alternative("motion"), v.alternative_values("motion"))
                                      : PrescribedMotion());
    region_.push_back(wall_region(v.alternative("shape"), v.alternative_values("shape"), dp, world.dim, layers,
                                  world.lo, world.hi));
    surface_.push_back(surface);
    // Every point of a wall's material lies within sqrt(3)/2 spacings of one of its particles.
    crossing_reach_ = std::max(crossing_reach_, dp);
    moves_ = moves_ || motion_.back().moves();
  }
  count_ = s.size() - first_;
  ranges_ = {RowRange{first_, count_, 0}};
  if (moves_) {
    s.require(wall_position0);
    const auto x = s.position().subspan(first_, count_);
    std::ranges::copy(x, start_positions(s, first_, count_).begin());
  }
}

void DynamicParticles::bind(World& world, const sph::FluidSettings& settings) {
  settings_ = settings;
  mirror_ = slip_ == sph::WallSlip::free_slip || (no_slip_ == NoSlip::extrapolated && settings.viscous_velocity);
  if (mirror_) {
    FieldInfo field = wall_viscous_velocity;
    field.single_when_mixed = walls_in_float(world.boundary);  // in the type of the wall velocity it mirrors
    world.boundary.require(field);
  }
  find_ghosts(world);
  rho0_of_material_.assign(world.materials.size(), 0.0);
  for (std::size_t m = 0; m < world.materials.size(); ++m) rho0_of_material_[m] = world.materials[m].density;
  // Moving walls start with their prescribed velocity (an impulsively started lid moves from the first step).
  if (moves_)
    with_wall_fields(world.boundary, first_, count_, [&](auto w) {
      const auto x0 = start_positions(world.boundary, first_, count_);
      for (std::size_t k = 0; k < count_; ++k) w.v[k] = motion_[slot_of_body_[w.body[k]]].velocity(x0[k], world.time);
    });
  lay_out(world);
  initial_density(world);
  update_pressure(world);
}

void DynamicParticles::lay_out(World& world) {
  // Per-material index lists for the EOS batch calls (indices in world.boundary).
  by_material_.assign(world.materials.size(), {});
  // Cell lists over the fluid's bounds and the walls' own (walls may sit
  // outside the domain); moving walls are clamped into the edge cells.
  Vec3 lo = settings_.lo, hi = settings_.hi;
  const auto material = world.boundary.material();
  const auto position = world.boundary.position();
  for (const RowRange& r : ranges_)
    for (std::size_t i = r.first; i < r.first + r.count; ++i) {
      by_material_[material[i]].push_back(static_cast<Index>(i));
      for (int a = 0; a < world.dim; ++a) {
        lo[a] = std::min(lo[a], position[i][a]);
        hi[a] = std::max(hi[a], position[i][a] + 1e-9);
      }
    }
  cells_.resize(ranges_.size());
  for (NeighbourGrid& cells : cells_) cells.configure(world.dim, lo, hi, settings_.kernel->support_radius(), world.periodic);
  build_cells(world);
  refresh_inverse_density(world);
  refresh_sets(world);
}

void DynamicParticles::build_cells(World& world) {
  const auto x = world.boundary.position();
  for (std::size_t k = 0; k < ranges_.size(); ++k) cells_[k].build(x.subspan(ranges_[k].first, ranges_[k].count));
}

// DBC needs only the fluid within one support radius of each wall particle,
// which the halo holds. mDBC's ghost nodes lie up to two wall depths inside
// the fluid: reach_beyond_radius() widens the halo by that much.
std::string DynamicParticles::why_not_on_ranks() const { return {}; }

// On several ranks this model holds every wall particle of the store, which
// the host lays out as one range of rows (owned, then halo) beside the block
// particles of other models, and the rows came in a new order.
void DynamicParticles::rows_moved(World& world) {
  const ParticleStore& s = world.boundary;
  const auto body = s.body();
  auto mine = [&](std::size_t i) { return slot_of_body_[body[i]] >= 0; };
  // My rows among the owned ones, then among the halo ones: one run each (ranks.cpp).
  ranges_.clear();
  count_ = 0;
  for (const auto [from, to] : {std::pair{std::size_t{0}, s.owned_size()}, std::pair{s.owned_size(), s.size()}}) {
    std::size_t first = from;
    while (first < to && !mine(first)) ++first;
    std::size_t end = first;
    while (end < to && mine(end)) ++end;
    for (std::size_t i = end; i < to; ++i)
      if (mine(i))
        throw RunError("error: wall '" + world.bodies[body[i]].name + "' has particles apart from the others of its "
                       "dynamic_particles model among this rank's " + (from == 0 ? "owned" : "halo") + " rows");
    if (end == first) continue;
    if (!ranges_.empty() && ranges_.back().first + ranges_.back().count == first)
      ranges_.back().count += end - first;  // the owned and the halo rows meet
    else
      ranges_.push_back({first, end - first, count_});
    count_ += end - first;
  }
  first_ = ranges_.empty() ? 0 : ranges_.front().first;
  find_ghosts(world);
  lay_out(world);
}

// A wall set per range of rows: the stage's fluid-wall passes read each.
void DynamicParticles::refresh_sets(World& world) {
  sets_.resize(ranges_.size());
  for (std::size_t k = 0; k < ranges_.size(); ++k) {
    const RowRange& r = ranges_[k];
    sph::WallSet& set = sets_[k];
    set = sph::WallSet{};
    set.cells = &cells_[k];
    set.position = world.boundary.position().subspan(r.first, r.count);
    with_wall_fields(world.boundary, r.first, r.count, [&](auto w) {
      using Real = typename decltype(w.rho)::value_type;
      auto fields = w.neighbours();
      fields.inv_density = inv_rho_.as<Real>().data() + r.offset;
      const auto* viscous = mirror_ ? viscous_velocity<Real>(world).data() + r.first : w.v.data();
      if constexpr (std::is_same_v<Real, float>) {
        set.single_fields = fields;
        set.viscous_velocity_single = viscous;
      } else {
        set.fields = fields;
        set.viscous_velocity = viscous;
      }
    });
  }
}

// Wall pressure extrapolated from the fluid around each wall particle
// (Adami et al. 2012): p_b = sum_f W_bf (p_f + rho_f g . (x_b - x_f)) / sum_f W_bf,
// then rho_b = rho(p_b) from the wall material's EOS, never below rho0.
// At the start, before any rank shares the particles out: one range.
void DynamicParticles::initial_density(World& world) {
  ParticleStore& fs = world.fluid;
  if (fs.size() == 0) return;
  const KernelTable& k = *settings_.kernel;
  const NeighbourGrid& fluid_cells = *settings_.cells;
  const Vec3 g = world.gravity;
  const std::span<const Vec3> wx = world.boundary.position().subspan(first_, count_);
  const auto wall_material = world.boundary.material().subspan(first_, count_);
  auto start = [&](Index) { return sph::ExtrapolationSums{}; };
  world.boundary.visit_scalar(wall_density.name, [&](auto all_rho) {
    const auto rho = all_rho.subspan(first_, count_);
    auto finish = [&](Index i, const sph::ExtrapolationSums& s) {
      if (s.wsum <= 0.0) return;
      const Material& mat = world.materials[wall_material[i]];
      const double pb = std::max(0.0, s.psum / s.wsum);
      rho[i] = std::max(mat.density, mat.eos->density_at(pb));
    };
    // The fluid's pressure and density in the type they are kept in (the stage keeps them alike).
    auto extrapolate = [&](auto fp, auto frho) {
      sph::pair_pass(count_, wx, fluid_cells, k, sph::other_set, start, finish,
                     sph::PressureExtrapolation{fp.data(), frho.data(), g});
    };
    if (fs.info("density").type == FieldType::scalar_f32)
      extrapolate(fs.scalar_f32("pressure"), fs.scalar_f32("density"));
    else
      extrapolate(fs.scalar("pressure"), fs.scalar("density"));
  });
}

void DynamicParticles::update_pressure(World& world) {
  with_wall_fields(world.boundary, 0, world.boundary.size(), [&](auto w) {
    for (std::size_t m = 0; m < by_material_.size(); ++m)
      if (!by_material_[m].empty())
        pressure_of(*world.materials[m].eos, by_material_[m], w.rho.data(), w.p.data(), w.c.data());
  });
}

void DynamicParticles::begin_step(World& world) {
  for (const RowRange& r : ranges_)
    with_wall_fields(world.boundary, r.first, r.count, [](auto w) { std::ranges::copy(w.rho, w.rho_n.begin()); });
}

void DynamicParticles::hold_fluid(World& world, double time) {
  ParticleStore& fluid = world.fluid;
  const std::size_t n = fluid.owned_size();  // another rank puts back its own particles
  if (n == 0 || count_ == 0) return;
  const auto x = fluid.position();
  const auto wall_body = world.boundary.body();
  const double reach = crossing_reach_;
  const int* slot_of_body = slot_of_body_.data();
  // Each thread lists what it finds in its static chunk of rows: read thread
  // by thread, the lists are in row order.
  const int threads = n >= sph::parallel_min ? omp_get_max_threads() : 1;
  near_by_thread_.resize(std::max<std::size_t>(near_by_thread_.size(), threads));
  for (auto& near : near_by_thread_) near.clear();  // the team may be smaller than asked
#pragma omp parallel num_threads(threads)
  {
    std::vector<NearWall>& near = near_by_thread_[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      std::int32_t slot = -1;
      for (std::size_t k = 0; k < ranges_.size(); ++k) {
        const std::int32_t* body = wall_body.data() + ranges_[k].first;
        cells_[k].for_each_neighbour(x[i], reach, [&](Index b, const Vec3&, double) { slot = slot_of_body[body[b]]; });
      }
      if (slot >= 0) near.push_back({static_cast<Index>(i), slot});
    }
  }
  for (const auto& near : near_by_thread_)
    for (const auto [i, slot] : near) {
      const PrescribedMotion& motion = motion_[slot];
      const Vec3 x0 = motion.initial_position(x[i], time);
      if (!region_[slot](x0)) continue;
      const Vec3 surface = motion.position(surface_[slot](x0), time);
      const Vec3 out = surface - x[i];  // out of the wall, into the fluid
      const Vec3 normal = norm(out) > 0.0 ? out * (1.0 / norm(out)) : Vec3{};
      crossings_.put_back(world, i, surface, normal, motion.velocity(surface_[slot](x0), time),
                          static_cast<std::size_t>(slot), "wall '" + body_names_[slot] + "'", time);
    }
}

void DynamicParticles::refresh_wall_sets(World& world) {
  if (moves_) build_cells(world);  // a restart loads the positions
  place_ghosts(world, world.time);
  refresh_sets(world);
}

std::uint64_t DynamicParticles::fill_wall_state(World& world, const sph::FluidView& fluid) {
  if (moves_) build_cells(world);  // also right after a restart, which loads the positions
  const std::uint64_t pairs = method_ == Method::mdbc ? fill_from_ghost_nodes(world, fluid) : fill_continuity(world, fluid);
  refresh_sets(world);
  return pairs;
}

void DynamicParticles::find_ghosts(World& world) {
  if (method_ != Method::mdbc) return;
  ghost0_.resize(count_);
  for (const RowRange& r : ranges_) {
    const WallFieldsOf<double> w(world.boundary, r.first, r.count);  // mDBC walls stay in double
    const std::span<const Vec3> x0 = moves_ ? start_positions(world.boundary, r.first, r.count) : w.x;
    for (std::size_t b = 0; b < r.count; ++b) {
      const Vec3& p = x0[b];
      ghost0_[r.offset + b] = surface_[slot_of_body_[w.body[b]]](p) * 2.0 - p;
      ghost_reach_ = std::max(ghost_reach_, norm(ghost0_[r.offset + b] - p));
    }
  }
  ghost_ = ghost0_;
  place_ghosts(world, world.time);
}

void DynamicParticles::place_ghosts(World& world, double time) {
  if (!moves_ || method_ != Method::mdbc) return;
  for (const RowRange& r : ranges_) {
    const WallFieldsOf<double> w(world.boundary, r.first, r.count);
    for (std::size_t b = 0; b < r.count; ++b)
      ghost_[r.offset + b] = wrap_periodic(world, motion_[slot_of_body_[w.body[b]]].position(ghost0_[r.offset + b], time));
  }
}

// mDBC: density (then pressure) and the viscous velocity from the ghost nodes.
// On several ranks for the particles this rank owns; the halo copies' values
// come from their owners after it.
std::uint64_t DynamicParticles::fill_from_ghost_nodes(World& world, const sph::FluidView& fluid) {
  const std::size_t owned = owned_count(world);
  const std::size_t first = ranges_.empty() ? 0 : ranges_.front().first;
  // mDBC walls stay in double: the ghost-node solve writes the wall pressure and viscous velocity in double.
  const std::span<Vec3> viscous = viscous_velocity<double>(world);
  const WallFieldsOf<double> mine(world.boundary, first, owned);
  const std::uint64_t pairs = sph::extrapolate_from_ghost_nodes(
      world.dim, {mine.x, std::span<const Vec3>(ghost_).first(owned), mine.v}, fluid, *settings_.kernel, slip_,
      mine.p, viscous.empty() ? viscous : viscous.subspan(first, owned));
  // The wall density from its material's EOS, never below rho0 (as DBC: a wall never pulls the fluid).
  std::vector<double>& inv_rho = inv_rho_.as<double>();
  inv_rho.resize(count_);
  for (const RowRange& r : ranges_) {
    const WallFieldsOf<double> w(world.boundary, r.first, r.count);
    for (std::size_t b = 0; b < r.count; ++b) {
      const Material& mat = world.materials[w.mat[b]];
      w.rho[b] = std::max(mat.density, mat.eos->density_at(std::max(0.0, w.p[b])));
      inv_rho[r.offset + b] = 1.0 / w.rho[b];
    }
  }
  update_pressure(world);
  if (world.parallel().ranks() > 1) {
    static const std::string values[] = {wall_density.name, wall_pressure.name, wall_sound_speed.name,
                                         wall_viscous_velocity.name};
    world.parallel().refresh_halo(world.boundary, std::span(values).first(viscous.empty() ? 3 : 4));
    refresh_inverse_density(world);
  }
  return pairs;
}

void DynamicParticles::refresh_inverse_density(World& world) {
  for (const RowRange& r : ranges_)
    with_wall_fields(world.boundary, r.first, r.count, [&](auto w) {
      using Real = typename decltype(w.rho)::value_type;
      std::vector<Real>& inv_rho = inv_rho_.as<Real>();
      inv_rho.resize(count_);
      for (std::size_t b = 0; b < r.count; ++b) inv_rho[r.offset + b] = static_cast<Real>(1.0 / w.rho[b]);
    });
}

std::size_t DynamicParticles::owned_count(const World& world) const {
  if (ranges_.empty()) return 0;
  const std::size_t owned = world.boundary.owned_size();
  const RowRange& r = ranges_.front();
  return owned > r.first ? std::min(r.count, owned - r.first) : 0;
}

// DBC: the wall particles' continuity rates (for the ones this rank owns).
std::uint64_t DynamicParticles::fill_continuity(World& world, const sph::FluidView& fluid) {
  // 1/rho from the current density (also right after a restart, which loads the density only).
  refresh_inverse_density(world);
  const std::size_t owned = owned_count(world);
  const std::size_t first = ranges_.empty() ? 0 : ranges_.front().first;
  const KernelTable& kernel = *settings_.kernel;
  // The walls and the fluid each in the type they are kept in.
  const std::uint64_t pairs = with_wall_fields(world.boundary, first, owned, [&](auto w) {
    using Real = typename decltype(w.rho)::value_type;
    // Continuity of each wall particle with its fluid neighbours and, for the
    // extrapolated no-slip, the mirrored velocity v_b* = 2 v_b - v~_b.
    auto start = [&](Index b) { return WallSums{w.v[b], w.rho[b], 0.0, 0.0, Vec3{}}; };
    const auto mirrored = mirror_ ? viscous_velocity<Real>(world).subspan(first, owned) : decltype(w.v){};
    auto finish = [&](Index b, const WallSums& s) { w.drho[b] = s.drho; };
    auto finish_mirror = [&](Index b, const WallSums& s) {
      w.drho[b] = s.drho;
      // No fluid in reach: nothing to mirror, the wall's own velocity.
      mirrored[b] = s.wsum > 0.0 ? w.v[b] * 2.0 - s.vsum * (1.0 / s.wsum) : Vec3(w.v[b]);
    };
    const std::span<const Vec3> wx = w.x;
    return fluid.visit_neighbours([&](const auto& nb) {
      const sph::Continuity continuity{nb};
      if (!mirror_) return sph::pair_pass(owned, wx, *fluid.cells, kernel, sph::other_set, start, finish, continuity);
      return sph::pair_pass(owned, wx, *fluid.cells, kernel, sph::other_set, start, finish_mirror, continuity,
                            VelocityShepard{nb.velocity});
    });
  });
  if (mirror_) {
    // The halo copies were skipped: their values come from their owners.
    static const std::string fields[] = {wall_viscous_velocity.name};
    world.parallel().refresh_halo(world.boundary, fields);
  }
  return pairs;
}

void DynamicParticles::advance_walls(World& world, double time, double dt) {
  const double* rho0 = rho0_of_material_.data();
  for (const RowRange& r : ranges_)
    with_wall_fields(world.boundary, r.first, r.count, [&](auto w) {
      if (method_ == Method::dbc) {
#pragma omp parallel for schedule(static) if (r.count >= 4096)
        for (std::size_t b = 0; b < r.count; ++b) {
          // DualSPHysics: a wall particle never goes below rho0, so walls never pull fluid.
          w.rho[b] = std::max(rho0[w.mat[b]], w.rho_n[b] + dt * w.drho[b]);
        }
      }
      if (moves_) {
        const auto x0 = start_positions(world.boundary, r.first, r.count);
#pragma omp parallel for schedule(static) if (r.count >= 4096)
        for (std::size_t b = 0; b < r.count; ++b) {
          const PrescribedMotion& motion = motion_[slot_of_body_[w.body[b]]];
          // A wall moving along a periodic axis (the lid of a Couette cell) stays in the period.
          w.x[b] = wrap_periodic(world, motion.position(x0[b], time));
          w.v[b] = motion.velocity(x0[b], time);
        }
      }
    });
  place_ghosts(world, time);
  update_pressure(world);
}

void DynamicParticles::describe_passes(StagePlan& plan) const {
  std::string names;
  for (const auto& n : body_names_) names += (names.empty() ? "'" : ", '") + n + "'";
  plan.passes.push_back("fluid-wall pass (dynamic_particles " + names +
                        "): the stage's pressure + viscosity + continuity against the wall set");
  if (method_ == Method::mdbc)
    plan.passes.push_back("ghost-node pass (dynamic_particles mdbc " + names +
                          "): first-order density at the mirrored ghost nodes" +
                          (!mirror_                                 ? ""
                           : slip_ == sph::WallSlip::free_slip ? ", free-slip velocity (normal part mirrored)"
                                                                : ", no-slip velocity 2 v_wall - v_ghost") +
                          ", wall EOS" + (moves_ ? ", prescribed motion" : ""));
  else
    plan.passes.push_back("wall-fluid pass (dynamic_particles " + names + "): wall continuity" +
                          (mirror_ ? ", extrapolated no-slip velocity 2 v_wall - Shepard(v_fluid)" : "") +
                          ", wall EOS" + (moves_ ? ", prescribed motion" : ""));
}

}  // namespace talus::boundary
