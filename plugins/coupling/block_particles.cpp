#include "block_particles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fluid_fit.hpp"
#include "talus/blocks.hpp"
#include "talus/dda/polyhedron.hpp"
#include "talus/eos.hpp"
#include "talus/error.hpp"
#include "talus/periodic.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/sph/pair_loop.hpp"
#include "talus/sph/wall_fields.hpp"
#include "talus/world.hpp"

namespace talus::coupling {

namespace {

using sph::wall_velocity;
using sph::wall_density;
using sph::wall_pressure;
using sph::wall_mass;
using sph::wall_sound_speed;
using sph::wall_density_rate;
using sph::wall_density_n;
using sph::wall_viscous_velocity;

const FieldInfo block_offset{"block_offset", FieldType::vector, "m", false, true};

// Body-frame lattice points inside the polyhedron, at most `layers` spacings
// deep below one of the faces in `covered` (empty: all faces). The lattice
// fills the bounding box with n_a = round(extent_a / dp) points per axis at
// spacing extent_a / n_a (within dp/2n_a of dp), so that the first layer lies
// half a spacing inside both faces of every axis: DBC particles then end
// exactly on the faces of a box, as the fluid's first row is fitted to end on
// them (fluid_fit.hpp). A lattice of spacing dp itself, centred, would put it
// (extent - (n-1) dp)/2 inside: dp/3 for a 0.2 m box at dp 0.03, which made
// the box look 0.5 dp wider to the fluid and float 11 % high.
struct Shell {
  std::vector<Vec3> points;
  Vec3 spacing;
};

// mDBC ghost node of a body-frame point inside the polyhedron: its mirror
// image across the nearest of the faces in `covered` (empty: all), or across
// all the faces it is equally near (to round-off: through their edge or
// corner), so that the images of a symmetric block stay symmetric.
Vec3 ghost_offset(const Polyhedron& poly, const Vec3& p, const std::vector<char>& covered, double dp) {
  auto depth_below = [&](std::size_t f) { return poly.offsets[f] - dot(poly.normals[f], p); };
  double nearest = 1e300;
  for (std::size_t f = 0; f < poly.normals.size(); ++f)
    if (covered.empty() || covered[f]) nearest = std::min(nearest, depth_below(f));
  Vec3 ghost = p;
  for (std::size_t f = 0; f < poly.normals.size(); ++f)
    if ((covered.empty() || covered[f]) && depth_below(f) <= nearest + 1e-9 * dp)
      ghost += poly.normals[f] * (2.0 * depth_below(f));
  return ghost;
}

Shell shell_points(const Polyhedron& poly, double dp, int layers, const std::vector<char>& covered) {
  Vec3 lo = poly.vertices[0], hi = lo;
  for (const Vec3& v : poly.vertices)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], v[a]);
      hi[a] = std::max(hi[a], v[a]);
    }
  int n[3];
  Vec3 start, step;
  for (int a = 0; a < 3; ++a) {
    const double extent = hi[a] - lo[a];
    n[a] = std::max(1, static_cast<int>(std::lround(extent / dp)));
    step[a] = extent > 0.0 ? extent / n[a] : dp;
    start[a] = lo[a] + 0.5 * step[a];
  }
  const double depth = layers * std::max({step.x, step.y, step.z});
  Shell out{{}, step};
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const Vec3 p{start.x + i * step.x, start.y + j * step.y, start.z + k * step.z};
        const double d = dda::plane_distance(poly, p);
        if (!(d < -1e-9 * dp)) continue;  // outside or on the surface
        double below = -1e300;            // depth below the nearest covered face (negative)
        for (std::size_t f = 0; f < poly.normals.size(); ++f)
          if (covered.empty() || covered[f]) below = std::max(below, dot(poly.normals[f], p) - poly.offsets[f]);
        if (below > -depth) out.points.push_back(p);
      }
  return out;
}

}  // namespace

ParamSet BlockParticles::describe() {
  ParamSet p{"block_particles",
             "boundary particles moving with a DDA block (DBC, as DualSPHysics floating bodies): the block pushes "
             "the fluid and the fluid's pressure and viscous forces act back on the block"};
  p.real("dp").unit("m").greater_than(0.0).optional().doc("spacing of the block's particles (default: the fluid's dp)");
  p.integer("layers").min(1).optional().doc("layers of particles inside the faces (default: enough to cover the "
                                            "kernel support)");
  p.string("material").optional().doc("fluid material whose reference density and EOS the block's particles use "
                                      "(default: the scene's only fluid material)");
  p.vector_list("faces").optional().doc("outward normals (scene frame, at t = 0) of the only faces that get "
                                        "particles, e.g. the top of a fixed slope (default: every face)");
  p.choice("method", {"dbc", "mdbc"})
      .default_value("dbc")
      .doc("how the block particles get their density: dbc = continuity with the fluid, mdbc = extrapolated from "
           "ghost nodes mirrored across the block's faces (English et al. 2022)");
  p.choice("slip", {"no_slip", "free_slip"})
      .default_value("no_slip")
      .doc("free_slip (needs method mdbc): the viscous terms see the fluid's tangential velocity at the ghost node "
           "and its mirrored normal velocity; no_slip: the block's own velocity (dbc, and mdbc with artificial "
           "viscosity) or 2 v_block - v_ghost (mdbc with laminar or Laplacian viscosity)");
  return p;
}

BlockParticles::BlockParticles(const ParamValues& v) {
  mdbc_ = v.has("method") && v.string("method") == "mdbc";
  if (v.has("slip") && v.string("slip") == "free_slip") {
    if (!mdbc_)
      v.fail("slip", "free_slip needs \"method\": \"mdbc\": DBC block particles have no face normal to mirror the "
                     "fluid velocity about");
    slip_ = sph::WallSlip::free_slip;
  }
  if (v.has("dp")) dp_param_ = v.real("dp");
  if (v.has("layers")) layers_param_ = static_cast<int>(v.integer("layers"));
  if (v.has("material")) material_name_ = v.string("material");
  if (v.has("faces")) {
    faces_ = v.vectors("faces");
    for (Vec3& n : faces_) {
      if (!(norm(n) > 0.0)) v.fail("faces", "a face normal must not be zero");
      n = n / norm(n);
    }
  }
}

void BlockParticles::setup(World& world, std::span<const int> bodies) {
  // Geometry waits for bind(): world.blocks exists only after the dda stage's setup.
  for (int bi : bodies) {
    bodies_.push_back(bi);
    names_.push_back(world.bodies[bi].name);
  }
}

void BlockParticles::bind(World& world, const sph::FluidSettings& settings) {
  settings_ = settings;
  blocks_ = find_blocks(world, bodies_, "block_particles");
  material_ = coupling_material(world, bodies_.front(), "block_particles", material_name_);
  const Material& mat = world.materials[material_];
  if (!mat.eos)
    world.bodies[bodies_.front()].params.fail("boundary", "block_particles: material '" + mat.name +
                                                              "' has no \"eos\" for the block particles' pressure");
  rho0_ = mat.density;
  dp_ = dp_param_ > 0.0 ? dp_param_ : world.dp;
  const double radius = settings.kernel->support_radius();
  layers_ = layers_param_ > 0 ? layers_param_ : std::max(1, static_cast<int>(std::ceil(radius / dp_ - 1e-9)));

  // Fluid the host placed inside a block at the start goes: the blocks were
  // not there when the fluid body was filled.
  removed_ = clear_fluid_inside(world, blocks_, 0.5 * world.dp * (1.0 - 1e-6));

  ParticleStore& s = world.boundary;
  for (const FieldInfo* f : {&wall_velocity, &wall_density, &wall_pressure, &wall_mass, &wall_sound_speed,
                             &wall_density_rate, &wall_density_n, &block_offset})
    s.require(*f);
  const BlockSet& b = *world.blocks;
  rows_.clear();
  all_.clear();
  covered_.clear();
  fitted_ = 0;
  mirror_ = mdbc_ && (slip_ == sph::WallSlip::free_slip || settings.viscous_velocity);
  if (mirror_) s.require(wall_viscous_velocity);
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const Polyhedron& poly = b.shape[blocks_[k]];
    std::vector<char> covered;
    if (!faces_.empty()) {
      covered.assign(poly.normals.size(), 0);
      for (const Vec3& n : faces_) {
        bool found = false;
        for (std::size_t f = 0; f < poly.normals.size(); ++f)
          if (dot(rotate(b.orientation[blocks_[k]], poly.normals[f]), n) > 1.0 - 1e-6) covered[f] = 1, found = true;
        if (!found)
          world.bodies[bodies_[k]].params.fail("boundary", "block_particles: block '" + names_[k] +
                                                                "' has no face with the outward normal listed in "
                                                                "\"faces\"");
      }
    }
    covered_.push_back(covered);
    // The fluid's first row dp/2 outside the covered faces, as the block's first row is dp/2 inside them.
    fitted_ += fit_fluid_to_faces(world, blocks_[k], covered, material_);
    const Shell shell = shell_points(poly, dp_, layers_, covered);
    const std::vector<Vec3>& points = shell.points;
    const double mass = rho0_ * shell.spacing.x * shell.spacing.y * shell.spacing.z;  // the volume each one stands for
    if (points.empty())
      world.bodies[bodies_[k]].params.fail("shape", "block '" + names_[k] + "' holds no boundary particle at dp = " +
                                                        std::to_string(dp_) + "; give block_particles a smaller \"dp\"");
    const std::size_t first = s.append(points.size());
    auto off = s.vector("block_offset");
    auto rho = s.scalar("density");
    auto m = s.scalar("mass");
    auto mid = s.material();
    auto bid = s.body();
    for (std::size_t q = 0; q < points.size(); ++q) {
      off[first + q] = points[q];
      rho[first + q] = rho0_;
      m[first + q] = mass;
      mid[first + q] = material_;
      bid[first + q] = bodies_[k];
      all_.push_back(static_cast<Index>(first + q));
    }
    rows_.emplace_back(all_.end() - static_cast<std::ptrdiff_t>(points.size()), all_.end());
  }
  cells_.assign(blocks_.size(), NeighbourGrid{});
  for (auto& c : cells_) c.configure(world.dim, settings.lo, settings.hi, radius, world.periodic);
  inv_rho_.assign(s.size(), 0.0);  // indexed like world.boundary (only my range is used)
  find_ghost_offsets(world);
  ledger_.reset(blocks_.size());
  place(world);
  refresh_sets(world);
  initial_density(world);
  update_pressure(world);
}

// DBC block particles need the fluid within one support radius, which the
// halo holds; mDBC's ghost nodes lie up to two layers' depth inside the fluid:
// reach_beyond_radius() widens the halo by that much. The fluid's force on a
// block is summed over the ranks (ImpulseLedger), and every rank moves the
// blocks alike (the dda stage runs on every rank with the same forces).
std::string BlockParticles::why_not_on_ranks() const { return {}; }

// mDBC: each particle's ghost node in the body frame, found again from its
// body-frame offset whenever the rows move (on several ranks).
void BlockParticles::find_ghost_offsets(World& world) {
  if (!mdbc_) return;
  const ParticleStore& s = world.boundary;
  const BlockSet& b = *world.blocks;
  const auto off = s.vector("block_offset");
  ghost_offset_.assign(s.size(), Vec3{});
  for (std::size_t k = 0; k < blocks_.size(); ++k)
    for (const Index p : rows_[k]) {
      ghost_offset_[p] = ghost_offset(b.shape[blocks_[k]], off[p], covered_[k], dp_);
      ghost_reach_ = std::max(ghost_reach_, norm(ghost_offset_[p] - off[p]));
    }
  place_ghosts(world);
}

void BlockParticles::rows_moved(World& world) {
  const ParticleStore& s = world.boundary;
  const auto body = s.body();
  for (auto& rows : rows_) rows.clear();
  all_.clear();
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto k = std::find(bodies_.begin(), bodies_.end(), body[i]);
    if (k == bodies_.end()) continue;
    rows_[static_cast<std::size_t>(k - bodies_.begin())].push_back(static_cast<Index>(i));
    all_.push_back(static_cast<Index>(i));
  }
  inv_rho_.assign(s.size(), 0.0);
  find_ghost_offsets(world);
  refresh_sets(world);
}

namespace {
// Rows in ascending order are one range when they span no more than their count.
bool is_one_range(const std::vector<Index>& rows) {
  return rows.back() - rows.front() + 1 == static_cast<Index>(rows.size());
}
}  // namespace

std::span<const Vec3> BlockParticles::positions_of(const World& world, std::size_t k) {
  const auto x = world.boundary.position();
  const std::vector<Index>& rows = rows_[k];
  if (rows.empty()) return {};
  // One range of rows (always on one rank): a view, no copy.
  if (is_one_range(rows)) return x.subspan(rows.front(), rows.size());
  outer_x_.resize(rows.size());
  for (std::size_t q = 0; q < rows.size(); ++q) outer_x_[q] = x[rows[q]];
  return outer_x_;
}

// Particles at the blocks' current poses with their rigid velocities.
void BlockParticles::place(World& world) {
  ParticleStore& s = world.boundary;
  const BlockSet& b = *world.blocks;
  auto x = s.position();
  auto v = s.vector("velocity");
  const auto off = s.vector("block_offset");
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const std::size_t i = blocks_[k];
    const Vec3 X = b.position[i], V = b.velocity[i], w = b.angular_velocity[i];
    const Quaternion q = b.orientation[i];
    for (const Index p : rows_[k]) {
      const Vec3 r = rotate(q, off[p]);
      x[p] = wrap_periodic(world, X + r);  // a block may straddle a periodic boundary: its particles stay inside
      v[p] = V + cross(w, r);
    }
  }
  place_ghosts(world);
}

void BlockParticles::place_ghosts(World& world) {
  if (!mdbc_) return;
  const BlockSet& b = *world.blocks;
  ghost_.resize(world.boundary.size());
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const std::size_t i = blocks_[k];
    for (const Index p : rows_[k]) ghost_[p] = wrap_periodic(world, b.position[i] + rotate(b.orientation[i], ghost_offset_[p]));
  }
}

void BlockParticles::initial_density(World& world) {
  ParticleStore& fs = world.fluid;
  if (fs.size() == 0) return;
  ParticleStore& s = world.boundary;
  const KernelTable& k = *settings_.kernel;
  // Its own grid of the fluid: bind() has just removed the fluid inside the
  // blocks and moved the fluid against them, so the stage's is out of date.
  NeighbourGrid fluid_cells;
  fluid_cells.configure(world.dim, settings_.lo, settings_.hi, k.support_radius(), world.periodic);
  fluid_cells.build(fs.position());
  const Material& mat = world.materials[material_];
  auto rho = s.scalar("density");
  for (std::size_t blk = 0; blk < blocks_.size(); ++blk) {
    const std::vector<Index>& rows = rows_[blk];
    auto start = [](Index) { return sph::ExtrapolationSums{}; };
    auto finish = [&](Index b, const sph::ExtrapolationSums& sum) {
      if (sum.wsum <= 0.0) return;
      rho[rows[b]] = std::max(rho0_, mat.eos->density_at(std::max(0.0, sum.psum / sum.wsum)));
    };
    sph::pair_pass(rows.size(), positions_of(world, blk), fluid_cells, k, sph::other_set, start, finish,
                   sph::PressureExtrapolation{fs.scalar("pressure").data(), fs.scalar("density").data(), world.gravity});
  }
}

void BlockParticles::update_pressure(World& world) {
  ParticleStore& s = world.boundary;
  world.materials[material_].eos->pressure(all_, s.scalar("density").data(), s.scalar("pressure").data(),
                                           s.scalar("sound_speed").data());
}

void BlockParticles::begin_step(World& world) {
  ParticleStore& s = world.boundary;
  auto rho = s.scalar("density");
  auto rho_n = s.scalar("density_n");
  for (Index p : all_) rho_n[p] = rho[p];
  ledger_.begin_step();
}

void BlockParticles::hold_fluid(World& world, double time) {
  ParticleStore& fluid = world.fluid;
  const std::size_t n = fluid.owned_size();  // another rank puts back its own particles
  const BlockSet& b = *world.blocks;
  const auto x = fluid.position();
  inside_.resize(n);
  impulse_.assign(blocks_.size(), Vec3{});
  angular_.assign(blocks_.size(), Vec3{});
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const std::size_t blk = blocks_[k];
    const Vec3 lo = b.bounds_lo[blk], hi = b.bounds_hi[blk], centre = b.position[blk];
    const Quaternion q = b.orientation[blk];
    const Polyhedron& poly = b.shape[blk];
    std::size_t found = 0;
#pragma omp parallel for schedule(static) reduction(+ : found) if (n >= sph::parallel_min)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 p = nearest_image(world, x[i], centre);
      inside_[i] = p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z &&
                   dda::plane_distance(poly, rotate_inverse(q, p - centre)) < 0.0;
      found += inside_[i];
    }
    if (found == 0) continue;
    for (std::size_t i = 0; i < n; ++i) {
      if (!inside_[i]) continue;
      const std::string what = "block '" + names_[k] + "'";
      if (!covered_[k].empty()) {  // it may have come in where the scene left no particles
        crossings_.count(world, i, k, what + " (its \"faces\" leave some faces without particles)", time);
        continue;
      }
      // Onto the nearest face (the least negative face distance), in the block's frame.
      const Vec3 arm = rotate_inverse(q, nearest_image(world, x[i], centre) - centre);
      std::size_t face = 0;
      for (std::size_t f = 1; f < poly.normals.size(); ++f)
        if (dot(poly.normals[f], arm) - poly.offsets[f] > dot(poly.normals[face], arm) - poly.offsets[face]) face = f;
      const Vec3 on_face = arm - poly.normals[face] * (dot(poly.normals[face], arm) - poly.offsets[face]);
      const Vec3 r = rotate(q, on_face);
      const Vec3 change = crossings_.put_back(world, i, centre + r, rotate(q, poly.normals[face]),
                                              b.velocity[blk] + cross(b.angular_velocity[blk], r), k, what, time);
      impulse_[k] -= change;  // action = reaction
      angular_[k] -= cross(r, change);
    }
  }
  ledger_.add_impulses(world, blocks_, impulse_, angular_, time);
}

void BlockParticles::refresh_sets(World& world) {
  ParticleStore& s = world.boundary;
  const BlockSet& b = *world.blocks;
  const std::span<const Vec3> x = s.position();
  const auto v = s.vector("velocity");
  const auto rho = s.scalar("density");
  const auto p = s.scalar("pressure");
  const auto c = s.scalar("sound_speed");
  const auto m = s.scalar("mass");
  const auto mat = s.material();
  sets_.resize(blocks_.size());
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    // The grid holds only this block's rows and reports them by their row in the store.
    cells_[k].build(x, rows_[k]);
    sph::WallSet& set = sets_[k];
    set.cells = &cells_[k];
    set.position = x;
    set.fields = {v.data(), rho.data(), p.data(), c.data(), m.data(), mat.data()};
    set.fields.inv_density = inv_rho_.data();
    set.viscous_velocity = mirror_ ? s.vector(wall_viscous_velocity.name).data() : set.fields.velocity;
    set.rigid_body = true;
    const std::size_t blk = blocks_[k];
    set.body = {b.position[blk], b.bounds_lo[blk], b.bounds_hi[blk]};
  }
}

std::uint64_t BlockParticles::fill_wall_state(World& world, const sph::FluidView& fluid) {
  refresh_sets(world);  // also right after a restart, which loads the positions
  return mdbc_ ? fill_from_ghost_nodes(world, fluid) : fill_continuity(world, fluid);
}

// mDBC: density (then pressure) and the viscous velocity from the ghost nodes,
// for the particles this rank owns (gathered: on several ranks a block's owned
// rows are no one range); the halo copies' values come from their owners.
std::uint64_t BlockParticles::fill_from_ghost_nodes(World& world, const sph::FluidView& fluid) {
  ParticleStore& s = world.boundary;
  const std::size_t owned = s.owned_size();
  const std::span<const Vec3> x = s.position();
  const auto v = s.vector("velocity");
  const auto rho = s.scalar("density");
  const auto p = s.scalar("pressure");
  const std::span<Vec3> viscous = mirror_ ? s.vector(wall_viscous_velocity.name) : std::span<Vec3>();
  const EquationOfState& eos = *world.materials[material_].eos;
  std::uint64_t pairs = 0;
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    nodes_.clear();
    for (const Index q : rows_[k])
      if (static_cast<std::size_t>(q) < owned) nodes_.add(q, x[q], ghost_[q], v[q]);
    nodes_.size_outputs(mirror_);
    pairs += sph::extrapolate_from_ghost_nodes(world.dim, {nodes_.wall, nodes_.ghost, nodes_.velocity}, fluid,
                                               *settings_.kernel, slip_, nodes_.pressure, nodes_.viscous);
    for (std::size_t j = 0; j < nodes_.rows.size(); ++j) {
      p[nodes_.rows[j]] = nodes_.pressure[j];
      if (mirror_) viscous[nodes_.rows[j]] = nodes_.viscous[j];
    }
  }
  // The density from the EOS, never below rho0 (as DBC: a block never pulls the fluid).
  for (const Index q : all_) rho[q] = std::max(rho0_, eos.density_at(std::max(0.0, p[q])));
  update_pressure(world);
  if (world.parallel().ranks() > 1) {
    static const std::string values[] = {wall_density.name, wall_pressure.name, wall_sound_speed.name,
                                         wall_viscous_velocity.name};
    world.parallel().refresh_halo(s, std::span(values).first(mirror_ ? 4 : 3));
  }
  for (const Index q : all_) inv_rho_[q] = 1.0 / rho[q];
  return pairs;
}

// DBC: the block particles' continuity rates.
std::uint64_t BlockParticles::fill_continuity(World& world, const sph::FluidView& fluid) {
  ParticleStore& s = world.boundary;
  const KernelTable& kernel = *settings_.kernel;
  const auto v = s.vector("velocity");
  const auto rho = s.scalar("density");
  auto drho = s.scalar("density_rate");
  const sph::Continuity continuity{fluid.neighbours()};  // of the block particles: the fluid's velocity and volume
  struct WallSums {
    Vec3 v;
    double rho = 0.0;
    double drho = 0.0;
  };
  const auto owned = static_cast<Index>(s.owned_size());
  std::uint64_t pairs = 0;
  for (std::size_t k = 0; k < blocks_.size(); ++k) {
    const std::vector<Index>& rows = rows_[k];
    for (const Index q : rows) inv_rho_[q] = 1.0 / rho[q];
    // The rows this rank owns, which come first (rows_ ascend): a halo copy's
    // density comes from its owner before the next evaluation reads it.
    const auto owned_rows = static_cast<std::size_t>(std::lower_bound(rows.begin(), rows.end(), owned) - rows.begin());
    auto start = [&](Index q) { return WallSums{v[rows[q]], rho[rows[q]], 0.0}; };
    auto finish = [&](Index q, const WallSums& sum) { drho[rows[q]] = sum.drho; };
    pairs += sph::pair_pass(owned_rows, positions_of(world, k), *fluid.cells, kernel, sph::other_set, start, finish,
                            continuity);
  }
  return pairs;
}

void BlockParticles::take_reaction(World&, std::size_t set, const Vec3& force, const Vec3& torque) {
  ledger_.set(set, force, torque);
}

void BlockParticles::advance_walls(World& world, double time, double dt) {
  ParticleStore& s = world.boundary;
  auto rho = s.scalar("density");
  const auto rho_n = s.scalar("density_n");
  const auto drho = s.scalar("density_rate");
  const double rho0 = rho0_;
  const std::size_t n = all_.size();
  const Index* ids = all_.data();
  if (!mdbc_) {  // mDBC filled the density in fill_wall_state
#pragma omp parallel for schedule(static)
    for (std::size_t q = 0; q < n; ++q) {
      const Index p = ids[q];
      rho[p] = std::max(rho0, rho_n[p] + dt * drho[p]);  // as DBC walls: never pull the fluid
    }
  }
  // The dda stage has already moved the blocks to the end of this host step.
  place(world);  // the grids follow in refresh_wall_sets or fill_wall_state, before any pass reads them
  update_pressure(world);
  ledger_.commit(world, blocks_, time, dt);
}

void BlockParticles::describe_passes(StagePlan& plan) const {
  std::string names;
  for (const auto& n : names_) names += (names.empty() ? "'" : ", '") + n + "'";
  std::size_t count = 0;
  for (const auto& rows : rows_) count += rows.size();
  plan.passes.push_back("fluid-block pass (block_particles " + names +
                        "): the stage's pressure + viscosity + continuity against each block's wall set; force and "
                        "torque on the block");
  plan.passes.push_back("block-fluid pass (block_particles " + names + "): " +
                        (mdbc_ ? std::string("mDBC density at ghost nodes mirrored across the faces") +
                                     (mirror_ ? (slip_ == sph::WallSlip::free_slip ? ", free-slip velocity"
                                                                                   : ", no-slip velocity 2 v_block - v_ghost")
                                              : "")
                               : std::string("block-particle continuity")) +
                        ", EOS, rigid placement");
  if (count) {
    char spacing[32];
    std::snprintf(spacing, sizeof spacing, "%g", dp_);
    plan.notes.push_back("block_particles " + names + ": " + std::to_string(count) + " particles in " +
                         std::to_string(layers_) + " layers at dp " + spacing + " m; " + std::to_string(fitted_) +
                         " fluid particles fitted to the faces at the start");
  }
}

}  // namespace talus::coupling
