#include "dda_stage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include <omp.h>

#include "block_shape.hpp"
#include "rigid_motion.hpp"
#include "talus/error.hpp"
#include "talus/world.hpp"

namespace talus::dda {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Largest gap, as a fraction of the contact margin, at which faces count as
// touching when the run starts (coordinates typed with 7 to 9 digits).
constexpr double bond_gap = 0.01;

double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

}  // namespace

ParamSet DdaStage::describe() {
  ParamSet p{"dda", "explicit 3D DDA: rigid polyhedral blocks, penalty contacts (seed sph-dda-rock-fluid-3d §2)"};
  p.real("safety").greater_than(0.0).max(1.0).default_value(0.5)
      .doc("fraction of the stable step 2/omega_max that is taken");
  p.boolean("subcycle").default_value(false)
      .doc("true: no time-step limit is reported to the host; each host step is split into as many stable DDA "
           "sub-steps as needed, with coupling forces held over the host step (coupled runs, coarser fluid step)");
  p.real("contact_margin").unit("m").min(0.0).optional()
      .doc("gap below which a contact is tracked, open, with its history (default 1% of the smallest block radius)");
  p.choice("joints", {"search", "initial_faces"}).default_value("search")
      .doc("search: contacts are sought at every step (blocks that move apart and meet again); initial_faces: the "
           "rigid-block-spring method for tessellated slopes: the joints are the faces that touch when the run "
           "starts, their springs fixed to both blocks at the corners of the shared polygon, and no contact is "
           "sought afterwards (vertex and edge contacts are dropped; small displacements only)");
  return p;
}

DdaStage::DdaStage(const ParamValues& v) : params_(v) {
  safety_ = v.real("safety");
  subcycle_ = v.boolean("subcycle");
  if (v.has("contact_margin")) margin_ = v.real("contact_margin");
  fixed_joints_ = v.string("joints") == "initial_faces";
}

void DdaStage::set_contact_model(int body, ContactModel* model) { overrides_.emplace_back(body, model); }

void DdaStage::setup(World& world) {
  bool any = false;
  for (const auto& body : world.bodies) any = any || body.kind == BodyKind::block;
  if (any && world.dim != 3) params_.fail("", "the dda stage is 3D only; this scene has domain.dim = 2");
  build_blocks(world);
  BlockSet& b = *world.blocks;
  const std::size_t n = b.size();
  if (n == 0) return;

  const int threads = omp_get_max_threads();
  fresh_.assign(threads, {});
  scratch_.assign(threads, {});
  pose_blocks(b);
  detect(b, true);
  update_time_step();
  update_energy(world, b);
}

void DdaStage::build_blocks(World& world) {
  if (world.blocks)
    params_.fail("", "the block system is already built by another stage (a dda or strength_reduction stage "
                     "earlier in the pipeline); list only one");
  world.blocks = std::make_unique<BlockSet>();
  energy_ = &world.blocks->energy;
  BlockSet& b = *world.blocks;
  for (std::size_t bi = 0; bi < world.bodies.size(); ++bi) {
    const Body& body = world.bodies[bi];
    if (body.kind != BodyKind::block) continue;
    const ParamValues& p = body.params;
    BlockGeometry g = block_geometry(p, body.name);
    if (!p.has("density")) p.fail("density", "block '" + body.name + "' needs a density (kg/m^3)");
    const double density = p.real("density");
    const bool fixed = p.has("fixed") && p.boolean("fixed");
    PrescribedMotion motion;
    if (p.has("motion")) motion = PrescribedMotion(p.alternative("motion"), p.alternative_values("motion"));
    if (fixed && motion.moves())
      p.fail("motion", "block '" + body.name + "' is fixed and has a motion; remove one of 'fixed' and 'motion'");
    const Vec3 v0 = p.has("velocity") ? p.vector("velocity") : Vec3{};
    const Vec3 w0 = p.has("angular_velocity") ? p.vector("angular_velocity") : Vec3{};
    if ((fixed || motion.moves()) && (norm2(v0) > 0.0 || norm2(w0) > 0.0))
      p.fail(norm2(v0) > 0.0 ? "velocity" : "angular_velocity",
             "block '" + body.name + "' is " + (fixed ? "fixed" : "moved by its motion") +
                 "; an initial velocity applies to free blocks only");

    ContactModel* model = nullptr;
    for (const auto& [index, m] : overrides_)
      if (index == static_cast<int>(bi)) model = m;
    if (!model) {
      Model* made = body.contact;  // made by the host from the body's "contact"
      model = dynamic_cast<ContactModel*>(made);
      if (made && !model) p.fail("contact", "block '" + body.name + "': the model is not a contact model");
    }
    if (!model)
      p.fail("contact", "block '" + body.name +
                            "' needs a contact model, e.g. \"contact\": {\"type\": \"penalty_coulomb\", ...}");
    auto it = std::find(models_.begin(), models_.end(), model);
    if (it == models_.end()) it = models_.insert(models_.end(), model);
    block_model_.push_back(static_cast<std::uint32_t>(it - models_.begin()));

    b.name.push_back(body.name);
    b.body.push_back(static_cast<int>(bi));
    b.fixed.push_back(fixed);
    b.kinematic.push_back(motion.moves());
    b.volume.push_back(g.props.volume);
    b.mass.push_back(density * g.props.volume);
    std::array<double, 9> inertia;
    for (int k = 0; k < 9; ++k) inertia[k] = density * g.props.inertia[k];
    b.inertia.push_back(inertia);
    b.position.push_back(g.props.centroid);
    b.orientation.push_back({});
    b.velocity.push_back(v0);
    b.angular_velocity.push_back(w0);
    b.external_force.push_back({});
    b.external_torque.push_back({});
    b.bounds_lo.push_back({});
    b.bounds_hi.push_back({});
    b.shape.push_back(std::move(g.shape));

    const bool dynamic = !fixed && !motion.moves();
    dynamic_.push_back(dynamic ? 1 : 0);
    inverse_mass_.push_back(dynamic ? 1.0 / b.mass.back() : 0.0);
    inverse_inertia_.push_back(inverse(inertia));
    const double radius = b.shape.back().radius;
    agility_.push_back(dynamic ? 1.0 / b.mass.back() + radius * radius / smallest_eigenvalue(inertia) : 0.0);
    momentum_.push_back(multiply(inertia, w0));  // orientation is the identity at t = 0
    motion_.push_back(std::move(motion));
    start_position_.push_back(b.position.back());
  }
  build_clumps(world, b);
  const std::size_t n = b.size();
  force_.assign(n, {});
  torque_.assign(n, {});
  stiffness_sum_.assign(n, 0.0);
  body_omega2_.assign(n, 0.0);
  inertia_scale_.assign(n, 1.0);
  posed_.assign(n, {});
  box_lo_.assign(n, {});
  box_hi_.assign(n, {});
  vertex_begin_.assign(n + 1, 0);
  face_begin_.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    vertex_begin_[i + 1] = vertex_begin_[i] + static_cast<std::uint32_t>(b.shape[i].vertices.size());
    face_begin_[i + 1] = face_begin_[i] + static_cast<std::uint32_t>(b.shape[i].faces.size());
  }
  world_vertices_.assign(vertex_begin_[n], {});
  world_normals_.assign(face_begin_[n], {});
  world_offsets_.assign(face_begin_[n], 0.0);
  if (margin_ < 0.0 && n > 0) {
    double smallest = b.shape[0].radius;
    for (const auto& s : b.shape) smallest = std::min(smallest, s.radius);
    margin_ = 0.01 * smallest;
  }
}

void DdaStage::pose_blocks(BlockSet& b) {
  const std::size_t n = b.size();
  const double half = 0.5 * margin_;
#pragma omp parallel for schedule(static) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i) {
    const Polyhedron& s = b.shape[i];
    const Quaternion q = b.orientation[i];
    const Vec3 x = b.position[i];
    Vec3* wv = world_vertices_.data() + vertex_begin_[i];
    Vec3 lo = x, hi = x;
    for (std::size_t k = 0; k < s.vertices.size(); ++k) {
      wv[k] = x + rotate(q, s.vertices[k]);
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], wv[k][a]);
        hi[a] = std::max(hi[a], wv[k][a]);
      }
    }
    Vec3* wn = world_normals_.data() + face_begin_[i];
    double* wo = world_offsets_.data() + face_begin_[i];
    for (std::size_t f = 0; f < s.faces.size(); ++f) {
      wn[f] = rotate(q, s.normals[f]);
      wo[f] = s.offsets[f] + dot(wn[f], x);
    }
    b.bounds_lo[i] = lo;
    b.bounds_hi[i] = hi;
    box_lo_[i] = lo - Vec3{half, half, half};
    box_hi_[i] = hi + Vec3{half, half, half};
    posed_[i] = {&s, wv, wn, wo, x};
  }
}

void DdaStage::detect(const BlockSet& b, bool initial) {
  if (fixed_joints_ && !initial) {
    place_fixed_joints(b);
    return;
  }
  broad_.find_pairs(box_lo_, box_hi_, dynamic_, pairs_);
  const std::size_t npairs = pairs_.size();
  const std::size_t threads = static_cast<std::size_t>(omp_get_max_threads());
  if (fresh_.size() < threads) {  // the host changed the thread count after setup
    fresh_.resize(threads);
    scratch_.resize(threads);
  }
  // Threads only pay off with many pairs (a parallel region costs microseconds).
#pragma omp parallel if (npairs > 2048)
  {
    const int t = omp_get_thread_num();
    auto& out = fresh_[t];
    auto& scratch = scratch_[t];
    out.clear();
    std::vector<ContactPoint>& points = scratch.points;
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < npairs; ++k) {
      const auto [i, j] = pairs_[k];
      if (lead_[i] == lead_[j]) continue;  // two blocks of one clump
      points.clear();
      collide(posed_[i], posed_[j], margin_, points, scratch);
      for (const auto& cp : points) out.push_back({cp, i, j});
    }
  }
  gathered_.clear();
  for (const auto& f : fresh_) gathered_.insert(gathered_.end(), f.begin(), f.end());
  const std::size_t n = gathered_.size();
  std::swap(contacts_, previous_);
  contacts_.resize(n);
  sort_order_.resize(n);
  std::iota(sort_order_.begin(), sort_order_.end(), 0u);
  auto key_of = [&](const Fresh& f) { return ContactKey{block_model_[f.a], f.a, f.b, f.point.feature}; };
  std::sort(sort_order_.begin(), sort_order_.end(),
            [&](std::uint32_t x, std::uint32_t y) { return key_of(gathered_[x]) < key_of(gathered_[y]); });
  for (std::size_t c = 0; c < n; ++c) {
    const Fresh& f = gathered_[sort_order_[c]];
    const ContactPoint& cp = f.point;
    contacts_.key[c] = key_of(f);
    contacts_.point[c] = cp.point;
    contacts_.normal[c] = cp.normal;
    contacts_.gap[c] = cp.gap;
    contacts_.area[c] = cp.area;
    contacts_.mass[c] = 1.0 / (inverse_mass_sum(f.a, f.b) * cp.manifold_size);
    contacts_.velocity[c] = b.velocity_at(f.b, cp.point) - b.velocity_at(f.a, cp.point);
  }
  contacts_.inherit(
      previous_,
      [&](std::uint32_t model) {
        return initial ? models_[model]->initial_state() : static_cast<std::uint8_t>(contact_open);
      },
      margin_);
  // A bond joins faces that touch at the start. Faces merely within the margin
  // (a gap the scene meant, not rounding) start unbonded: a bond across a gap
  // would pull them together with k_n times the gap.
  if (initial)
    for (std::size_t c = 0; c < n; ++c)
      if (contacts_.gap[c] > bond_gap * margin_) contacts_.state[c] &= static_cast<std::uint8_t>(~contact_bonded);
  if (initial && fixed_joints_) fix_joints(b);
  const std::size_t kept = contacts_.size();
  model_begin_.assign(models_.size() + 1, kept);
  for (std::size_t c = kept; c-- > 0;) model_begin_[contacts_.key[c].model] = c;
  for (std::size_t m = models_.size(); m-- > 0;) model_begin_[m] = std::min(model_begin_[m], model_begin_[m + 1]);
}

void DdaStage::contact_forces(BlockSet& b, double h) {
  for (std::size_t m = 0; m < models_.size(); ++m)
    if (model_begin_[m] < model_begin_[m + 1])
      models_[m]->compute(contacts_.batch(model_begin_[m], model_begin_[m + 1]), h);
  std::fill(force_.begin(), force_.end(), Vec3{});
  std::fill(torque_.begin(), torque_.end(), Vec3{});
  double strain = 0.0, dissipated = 0.0;
  slipping_ = 0;
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    const auto& k = contacts_.key[c];
    const Vec3 f = contacts_.force[c];
    const Vec3 p = contacts_.point[c];
    force_[k.b] += f;
    torque_[k.b] += cross(p - b.position[k.b], f);
    force_[k.a] -= f;
    torque_[k.a] -= cross(p - b.position[k.a], f);
    strain += contacts_.strain_energy[c];
    dissipated += contacts_.dissipated[c];
    slipping_ += (contacts_.state[c] & contact_state_mask) == contact_slip;
  }
  b.energy.strain = strain;
  b.energy.dissipated += dissipated;
  timing_.contact_points += contacts_.size();
}

void DdaStage::integrate(World& world, BlockSet& b, double t, double h) {
  const Vec3 g = world.gravity;
  const double kick = started_ ? h : 0.5 * h;  // leapfrog start: v(1/2) = v(0) + dt/2 a(0)
  double work = 0.0, kinetic = 0.0, potential = 0.0, damped = 0.0;
  double unbalanced = 0.0, weight = 0.0;
  std::size_t dynamic_count = 0;
  const std::size_t n = b.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!dynamic_[i] || lead_[i] != i) continue;
    // The body's centroid, and the forces on its blocks summed about it (for
    // a block on its own the centroid is the block's and the arms are zero).
    const Quaternion q = b.orientation[i];
    const Vec3 centre = b.position[i] - rotate(q, offset_[i]);
    Vec3 force{}, torque{}, applied{}, applied_torque{};
    for (std::uint32_t k = member_begin_[i]; k < member_begin_[i + 1]; ++k) {
      const std::uint32_t m = members_[k];
      const Vec3 arm = b.position[m] - centre;
      const Vec3 f = b.mass[m] * g + b.external_force[m] + force_[m];
      force += f;
      torque += b.external_torque[m] + torque_[m] + cross(arm, f);
      applied += b.external_force[m];
      applied_torque += b.external_torque[m] + cross(arm, b.external_force[m]);
      potential -= b.mass[m] * dot(g, b.position[m]);
    }
    const Vec3 w_old = b.angular_velocity[i], l_old = momentum_[i];
    const Vec3 v_old = b.velocity[i] - cross(w_old, b.position[i] - centre);
    unbalanced = std::max({unbalanced, norm(force), norm(torque) / body_radius_[i]});
    weight += body_mass_[i] * norm(g);
    ++dynamic_count;
    Vec3 damping_force{}, damping_torque{};
    if (local_damping_ > 0.0)
      for (int k = 0; k < 3; ++k) {
        damping_force[k] = -local_damping_ * std::abs(force[k]) * sign(v_old[k]);
        damping_torque[k] = -local_damping_ * std::abs(torque[k]) * sign(w_old[k]);
      }
    force += damping_force;
    torque += damping_torque;
    const double scale = inertia_scale_[i];
    const Vec3 v = v_old + (kick * inverse_mass_[i] / scale) * force;
    momentum_[i] += kick * torque;
    // Energies at the time of the forces, t: the leapfrog's synchronous
    // kinetic energy 1/2 m v(t-h/2).v(t+h/2) (exactly conserved with the
    // potential at t for linear forces); at the start v(-h/2) = 2 v(0) - v(h/2).
    const Vec3 v_before = started_ ? v_old : 2.0 * v_old - v;
    kinetic += 0.5 * scale * body_mass_[i] * dot(v_before, v);
    work += dot(applied, 0.5 * (v_before + v)) * h;
    // w(i+1/2) = I^-1 L(i+1/2) with the inertia at the mid-step orientation
    // (two fixed-point passes from the previous w).
    Vec3 w = w_old;
    for (int pass = 0; pass < 2; ++pass) {
      const Quaternion mid = normalised(from_rotation_vector((0.5 * h) * w) * q);
      w = rotate(mid, multiply(inverse_inertia_[i], rotate_inverse(mid, momentum_[i]))) / scale;
    }
    const Vec3 w_before = started_ ? w_old : 2.0 * w_old - w;
    const Vec3 l_before = started_ ? l_old : 2.0 * l_old - momentum_[i];
    kinetic += 0.25 * (dot(w_before, momentum_[i]) + dot(w, l_before));
    work += dot(applied_torque, 0.5 * (w_before + w)) * h;
    damped -= (dot(damping_force, 0.5 * (v_before + v)) + dot(damping_torque, 0.5 * (w_before + w))) * h;
    const Vec3 moved = centre + h * v;
    const Quaternion turned = normalised(from_rotation_vector(h * w) * q);
    if (!is_finite(moved) || !is_finite(w))
      throw RunError("step " + std::to_string(world.step) + " (t = " + format("%.6g", t) + " s): block '" +
                     b.name[i] + "' has a non-finite position or angular velocity; the time step is too large "
                     "for the contact stiffness or the contacts exploded");
    for (std::uint32_t k = member_begin_[i]; k < member_begin_[i + 1]; ++k) {
      const std::uint32_t m = members_[k];
      b.position[m] = moved + rotate(turned, offset_[m]);
      b.orientation[m] = turned;
      b.velocity[m] = v + cross(w, b.position[m] - moved);
      b.angular_velocity[m] = w;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (b.kinematic[i]) {
      // Work done on the system by the driven block over this step.
      work -= (dot(force_[i], b.velocity[i]) + dot(torque_[i], b.angular_velocity[i])) * h;
      move_kinematic(b, t + h);
    }
  b.energy.external_work += work;
  b.energy.dissipated += damped;
  b.energy.kinetic = kinetic;
  b.energy.potential = potential;
  unbalanced_ratio_ = weight > 0.0 ? unbalanced / (weight / dynamic_count) : 0.0;
  started_ = true;
}

void DdaStage::move_kinematic(BlockSet& b, double t) {
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!b.kinematic[i]) continue;
    const PrescribedMotion& m = motion_[i];
    const Vec3 x0 = start_position_[i];
    const double s = std::max(b.shape[i].radius, 1e-3);
    const Vec3 c = m.position(x0, t), vc = m.velocity(x0, t);
    Vec3 col[3], w{};
    for (int k = 0; k < 3; ++k) {
      Vec3 e{};
      e[k] = s;
      col[k] = m.position(x0 + e, t) - c;
      w += cross(col[k], m.velocity(x0 + e, t) - vc);
    }
    b.position[i] = c;
    b.orientation[i] = from_columns(col[0] / s, col[1] / s, col[2] / s);
    b.velocity[i] = vc;
    b.angular_velocity[i] = w / (2.0 * s * s);
  }
}

void DdaStage::update_time_step() {
  double k_max = 0.0, xi = 0.0;
  for (const ContactModel* m : models_) {
    k_max = std::max(k_max, m->max_stiffness());
    xi = std::max(xi, m->damping_ratio());
  }
  std::fill(stiffness_sum_.begin(), stiffness_sum_.end(), 0.0);
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    const auto& k = contacts_.key[c];
    const double stiffness = models_[k.model]->max_stiffness();
    stiffness_sum_[lead_[k.a]] += stiffness * (dynamic_[k.b] ? 2.0 : 1.0);
    stiffness_sum_[lead_[k.b]] += stiffness * (dynamic_[k.a] ? 2.0 : 1.0);
  }
  // Each dynamic body's own bound on omega^2; with mass scaling every body
  // takes the inertia that brings its own to the slowest body's.
  double omega2 = 0.0, slowest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < dynamic_.size(); ++i)
    if (dynamic_[i] && lead_[i] == i) {
      body_omega2_[i] = agility_[i] * std::max(stiffness_sum_[i], 8.0 * k_max);
      omega2 = std::max(omega2, body_omega2_[i]);
      slowest = std::min(slowest, body_omega2_[i]);
    }
  if (mass_scaling_ && omega2 > 0.0) {
    for (std::size_t i = 0; i < dynamic_.size(); ++i)
      if (dynamic_[i] && lead_[i] == i) inertia_scale_[i] = std::max(inertia_scale_[i], body_omega2_[i] / slowest);
    omega2 = slowest;
  }
  dt_stable_ = omega2 > 0.0 ? safety_ * 2.0 / std::sqrt(omega2) * (std::sqrt(1.0 + xi * xi) - xi)
                            : std::numeric_limits<double>::infinity();
}

void DdaStage::update_energy(World& world, BlockSet& b) {
  double kinetic = 0.0, potential = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!dynamic_[i]) continue;
    potential -= b.mass[i] * dot(world.gravity, b.position[i]);
    if (lead_[i] != i) continue;
    const Vec3 arm = rotate(b.orientation[i], offset_[i]);  // from the body's centroid to the lead's
    const Vec3 v = b.velocity[i] - cross(b.angular_velocity[i], arm);
    kinetic += 0.5 * inertia_scale_[i] * body_mass_[i] * norm2(v) + 0.5 * dot(b.angular_velocity[i], momentum_[i]);
  }
  b.energy.kinetic = kinetic;
  b.energy.potential = potential;
}

void DdaStage::step(World& world, BlockSet& b, double t, double h) {
  auto t0 = Clock::now();
  pose_blocks(b);
  detect(b, false);
  auto t1 = Clock::now();
  contact_forces(b, h);
  auto t2 = Clock::now();
  integrate(world, b, t, h);
  update_time_step();
  timing_.detection += std::chrono::duration<double>(t1 - t0).count();
  timing_.forces += std::chrono::duration<double>(t2 - t1).count();
  timing_.integration += seconds_since(t2);
  ++timing_.steps;
}

void DdaStage::relax_step(World& world) {
  if (world.blocks && world.blocks->size() > 0) step(world, *world.blocks, world.time, dt_stable_);
}

void DdaStage::stop_blocks(World& world) {
  BlockSet& b = *world.blocks;
  std::fill(b.velocity.begin(), b.velocity.end(), Vec3{});
  std::fill(b.angular_velocity.begin(), b.angular_velocity.end(), Vec3{});
  std::fill(momentum_.begin(), momentum_.end(), Vec3{});
  started_ = false;
}

double DdaStage::stable_time_step(World& /*world*/) {
  return subcycle_ ? std::numeric_limits<double>::infinity() : dt_stable_;
}

void DdaStage::advance(World& world, double dt) {
  if (!world.blocks || world.blocks->size() == 0) return;
  BlockSet& b = *world.blocks;
  int n = 1;
  if (std::isfinite(dt_stable_) && dt > dt_stable_) n = static_cast<int>(std::ceil(dt / dt_stable_ - 1e-9));
  const double h = dt / n;
  for (int k = 0; k < n; ++k) step(world, b, world.time + k * h, h);
  last_substeps_ = n;
  std::fill(b.external_force.begin(), b.external_force.end(), Vec3{});
  std::fill(b.external_torque.begin(), b.external_torque.end(), Vec3{});
}

StagePlan DdaStage::plan(const World& world) const {
  StagePlan p;
  const std::size_t n = world.blocks ? world.blocks->size() : 0;
  if (n == 0) {
    p.notes.push_back("no block bodies: the stage does nothing");
    return p;
  }
  p.passes = {"block poses (world vertices, bounding boxes)", "broad phase (sort and sweep)",
              "narrow phase (SAT + clipped manifold)", "contact models (one batch per model)",
              "central-difference update (exact rotation)"};
  p.writes = {"blocks"};
  p.reads = {"blocks.external_force", "blocks.external_torque"};
  p.notes.push_back(std::to_string(n) + " blocks, " + std::to_string(models_.size()) + " contact model(s)");
  p.notes.push_back(subcycle_ ? "sub-cycles inside the host step" : "limits the host step to its stable step");
  return p;
}

std::string DdaStage::status(const World& world) const {
  if (!world.blocks || world.blocks->size() == 0) return {};
  const BlockEnergy& e = world.blocks->energy;
  std::string s = std::to_string(contacts_.size()) + " contacts (" + std::to_string(slipping_) + " slip), dt " +
                  format("%.3g", dt_stable_) + " s";
  if (last_substeps_ > 1) s += " x " + std::to_string(last_substeps_) + " sub-steps";
  return s + ", E kin " + format("%.4g", e.kinetic) + " J, dissipated " + format("%.4g", e.dissipated) + " J";
}

}  // namespace talus::dda
