#include "strength_reduction.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "esri_ascii.hpp"
#include "file_io.hpp"
#include "handoff.hpp"
#include "slip_path.hpp"
#include "talus/blocks.hpp"
#include "talus/error.hpp"
#include "talus/output_name.hpp"
#include "talus/state_archive.hpp"
#include "talus/world.hpp"

namespace talus::strength_reduction {
namespace {

// The gravity-loaded state is relaxed with every strength multiplied by this
// (and bonds unbreakable in tension), so that no joint slips or breaks while
// the springs take up the weight.
constexpr double elastic_factor = 1e-6;

// Steps between displacement checks unless the scene or fixed joints say otherwise.
constexpr std::int64_t default_window = 500;

std::string number(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// Angle of the rotation from a to b, rad.
double rotation_angle(const Quaternion& a, const Quaternion& b) {
  const Quaternion r = conjugate(a) * b;
  return 2.0 * std::atan2(std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z), std::abs(r.w));
}

bool inside(const Polyhedron& s, const Vec3& body_point) {
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    if (dot(s.normals[f], body_point) > s.offsets[f] + 1e-9 * s.radius) return false;
  return true;
}

template <class Archive, class Trial>
void archive_trial(Archive& a, Trial& t) {
  a.value(t.factor);
  for (bool* flag : {&t.budget, &t.displaced, &t.growing, &t.slip_path}) {
    std::uint8_t v = *flag;
    a.value(v);
    *flag = v != 0;
  }
  a.value(t.steps);
  a.value(t.ratio);
  a.value(t.displacement);
  for (std::uint64_t* c : {&t.contacts, &t.open, &t.stick, &t.slip, &t.bonded, &t.released_blocks}) a.value(*c);
  a.value(t.released_mass);
  a.value(t.dissipated);
  a.value(t.wall_seconds);
  a.vector(t.monitors);
}

template <class Archive>
void archive_limit_state(Archive& a, LimitState& s) {
  std::uint8_t present = s.present;
  a.value(present);
  s.present = present != 0;
  a.value(s.factor);
  a.value(s.steps);
  a.value(s.ratio);
  a.vector(s.point);
  a.vector(s.normal);
  a.vector(s.force);
  a.vector(s.normal_force);
  a.vector(s.shear_force);
  a.vector(s.area);
  a.vector(s.gap);
  a.vector(s.state);
  a.vector(s.bonded);
  a.vector(s.block_a);
  a.vector(s.block_b);
  a.vector(s.position);
  a.vector(s.displacement);
  a.vector(s.orientation);
  a.vector(s.released);
}

// The joint strength under most of the slip surface (by contact area between
// released and holding blocks; a pair uses block a's model; every block has
// its own model, so joints count as one by their strength) and the share it
// covers. A tessellation's slip surface also runs along smooth walls, whose
// joint is not the ground's.
std::pair<const ReducedJoint*, double> slip_surface_joint(const LimitState& limit,
                                                          const std::vector<std::uint8_t>& released,
                                                          const std::vector<int>& body_of_block,
                                                          const std::vector<const ReducedJoint*>& joint_of_body) {
  std::vector<std::pair<const ReducedJoint*, double>> area;
  double total = 0.0;
  for (std::size_t c = 0; c < limit.block_a.size(); ++c) {
    if (released[limit.block_a[c]] == released[limit.block_b[c]]) continue;
    const ReducedJoint* joint = joint_of_body[body_of_block[limit.block_a[c]]];
    if (!joint) continue;
    auto it = std::find_if(area.begin(), area.end(), [&](const auto& e) {
      return e.first->base().cohesion == joint->base().cohesion &&
             e.first->base().tan_friction == joint->base().tan_friction;
    });
    if (it == area.end()) it = area.insert(area.end(), {joint, 0.0});
    it->second += limit.area[c];
    total += limit.area[c];
  }
  if (area.empty() || !(total > 0.0)) return {nullptr, 0.0};
  const auto most = std::max_element(area.begin(), area.end(),
                                     [](const auto& x, const auto& y) { return x.second < y.second; });
  return {most->first, most->second / total};
}

}  // namespace

ParamSet StrengthReduction::describe() {
  ParamSet p{"strength_reduction",
             "safety factor of a block slope: joints at c/F and tan(phi)/F, each trial relaxed to equilibrium, F "
             "bracketed and bisected (seed pfe-ie-depth-integrated-sph-landslide §2)"};
  p.object("dda", dda::DdaStage::describe()).optional()
      .doc("settings of the DDA block system the stage relaxes (it runs its own; do not list a dda stage too)");
  p.real_list("bracket").default_value(std::vector<double>{0.5, 4.0})
      .doc("[lo, hi]: the slope must hold at F = lo and fail at F = hi; the run stops with an error otherwise");
  p.real("tolerance").greater_than(0.0).default_value(0.005)
      .doc("width of the final bracket; F_s is its middle, so its error is at most half of this");
  p.real("ratio_limit").greater_than(0.0).less_than(1.0).default_value(1e-5)
      .doc("equilibrium: the largest unbalanced force (or torque / block radius) over the mean block weight "
           "falls below this");
  p.integer("max_steps").min(1).default_value(20000)
      .doc("step budget of one trial; a trial still out of equilibrium then fails ('no equilibrium')");
  p.real("damping").greater_than(0.0).less_than(1.0).default_value(0.8)
      .doc("local non-viscous damping coefficient alpha (3DEC): each force and torque component is reduced by "
           "alpha |F| against the block's velocity");
  p.boolean("mass_scaling").default_value(true)
      .doc("give each free body the inertia that brings its stable frequency down to the slowest body's "
           "(3DEC's density scaling for statics), so that small blocks no longer set the step; gravity keeps the "
           "true mass, so equilibria are unchanged");
  p.integer("window").min(10).optional()
      .doc("steps between displacement checks; a displacement that grows three windows running without "
           "slowing down fails the trial (default 500; with fixed joints the steps the gravity-loaded state took "
           "to settle, at least 500: a tessellation keeps moving for about that long before it settles, and "
           "shorter windows fail trials that would hold)");
  p.real("displacement_limit").unit("m").greater_than(0.0).optional()
      .doc("a block or monitor moving farther than this from the gravity-loaded state fails the trial "
           "(default 1% of the smallest free block's radius)");
  p.choice("failure", {"any", "collapse"}).optional()
      .doc("which criteria fail a trial (all are measured and reported): any: no equilibrium, the displacement "
           "limit or growth, or a slip path (free blocks held by slipping or open joints only); collapse: no "
           "equilibrium or the displacement criteria, not the slip path. Default any; collapse with fixed joints "
           "(dda.joints = initial_faces), because there a block whose joints all yield may still hold: its load "
           "comes from its neighbours' springs, which relax as it moves");
  p.vector_list("monitors").unit("m").optional()
      .doc("points inside free blocks whose displacement is reported for every trial (the seed's monitoring "
           "points)");
  ParamSet handoff{"handoff", "rasters and a run-out scene for the mass that fails"};
  handoff.path("runout_scene")
      .doc("a depth_integrated_sph scene (its kernel, Bingham material, time and outputs) that the hand-off fills "
           "with the failed mass, the terrain and the reduced strength and writes as FILE_runout.json");
  handoff.path("dem").optional()
      .doc("ESRI ASCII DEM of the slope around the blocks: the rasters take its grid, and the terrain its elevations "
           "except under the failed mass");
  handoff.real("cell").unit("m").greater_than(0.0).optional()
      .doc("raster cell, and the run-out particle spacing, without a dem (with one: the DEM's cell)");
  handoff.real("margin").unit("m").min(0.0).default_value(0.0)
      .doc("without a dem: the rasters cover the blocks' plan extent plus this on every side");
  handoff.choice("basal_shear", {"inverse_distance", "inverse_distance_linear"}).default_value("inverse_distance")
      .doc("how the limit-state shear of the slip-surface contacts reaches the cells: inverse_distance, weights "
           "1 / d (seed eq. 30; keeps constants and stays within the contacts' range, but does not reproduce a "
           "linear field); inverse_distance_linear, the same weights on each contact's value extended by the plane "
           "that fits its neighbours (Shepard's method with linear nodal functions: exact for a linear field, may "
           "leave the contacts' range)");
  p.object("handoff", handoff).optional()
      .doc("after the search: terrain (the DEM with the slip surface under the failed mass let into it; without a "
           "DEM, the blocks that hold), vertical thickness of the released blocks, limit-state basal shear by "
           "inverse distance (seed eq. 30), and a run-out scene reading them");
  p.string("file").default_value("strength_reduction")
      .doc("name of the per-trial table FILE.csv and the limit state FILE_limit_state.h5 in the output folder");
  check_output_name(p, "file");
  p.check([](const ParamValues& v, Diagnostics& d) {
    const auto& b = v.reals("bracket");
    if (b.size() != 2) {
      d.error(v, "bracket", "expected two factors [lo, hi], got " + std::to_string(b.size()));
      return;
    }
    if (!(b[0] > 0.0 && b[1] > b[0]))
      d.error(v, "bracket", "needs 0 < lo < hi, got [" + number("%g", b[0]) + ", " + number("%g", b[1]) + "]");
    else if (v.real("tolerance") >= b[1] - b[0])
      d.error(v, "tolerance", "must be smaller than the bracket's width " + number("%g", b[1] - b[0]));
  });
  return p;
}

StrengthReduction::StrengthReduction(const ParamValues& v)
    : params_(v), dda_(std::make_unique<dda::DdaStage>(v.object("dda"))) {
  tolerance_ = v.real("tolerance");
  ratio_limit_ = v.real("ratio_limit");
  damping_ = v.real("damping");
  max_steps_ = v.integer("max_steps");
  window_ = v.has("window") ? v.integer("window") : default_window;
  if (v.has("displacement_limit")) displacement_limit_ = v.real("displacement_limit");
  file_ = v.string("file");
  if (v.has("handoff")) {
    const ParamValues& h = v.object("handoff");
    handoff_ = true;
    handoff_margin_ = h.real("margin");
    if (h.has("cell")) handoff_cell_ = h.real("cell");
    basal_shear_ = h.string("basal_shear") == "inverse_distance_linear" ? BasalShear::inverse_distance_linear
                                                                         : BasalShear::inverse_distance;
  }
  const auto& b = v.reals("bracket");
  search_ = FactorSearch(b[0], b[1], tolerance_);
  trial_budget_ = 1 + search_.max_trials();
}

void StrengthReduction::setup(World& world) {
  if (world.blocks)
    params_.fail("", "the block system is already built by another stage; strength_reduction runs its own DDA, "
                     "so list no dda stage beside it");
  if (norm(world.gravity) == 0.0)
    params_.fail("", "strength reduction loads the slope by its weight; the scene has no gravity");
  for (std::size_t bi = 0; bi < world.bodies.size(); ++bi) {
    const Body& body = world.bodies[bi];
    if (body.kind != BodyKind::block || !body.params.has("contact")) continue;
    joints_.push_back(std::make_unique<ReducedJoint>(body.params.model_name("contact"),
                                                     body.params.model_params("contact"), body.params));
    dda_->set_contact_model(static_cast<int>(bi), joints_.back().get());
    joint_of_body_.resize(world.bodies.size(), nullptr);
    joint_of_body_[bi] = joints_.back().get();
  }
  if (handoff_) {
    const ParamValues& h = params_.object("handoff");
    if (h.has("dem")) {
      dem_ = h.read_file("dem", [](const std::string& f) { return runout::read_esri_ascii(f); });
      has_dem_ = true;
      if (handoff_cell_ > 0.0 && std::abs(handoff_cell_ - dem_.cell) > 1e-9 * dem_.cell)
        h.fail("cell", "the rasters take the DEM's cell " + number("%g", dem_.cell) + " m; leave out cell or "
                       "give the same");
      handoff_cell_ = dem_.cell;
    } else if (!(handoff_cell_ > 0.0)) {
      h.fail("cell", "without a dem the hand-off needs a raster cell (m)");
    }
    runout_template_ = h.read_file("runout_scene", read_runout_template);
  }
  const bool collapse = params_.has("failure") ? params_.string("failure") == "collapse" : dda_->fixed_joints();
  by_slip_path_ = !collapse;
  dda_->set_mass_scaling(params_.boolean("mass_scaling"));
  dda_->setup(world);
  dda_->set_local_damping(damping_);
  check_start(world);
  locate_monitors(world);
  if (displacement_limit_ < 0.0) {
    const BlockSet& b = *world.blocks;
    double smallest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < b.size(); ++i)
      if (!b.fixed[i]) smallest = std::min(smallest, b.shape[i].radius);
    displacement_limit_ = 0.01 * smallest;
  }
}

void StrengthReduction::check_start(const World& world) const {
  if (!world.blocks || world.blocks->size() == 0)
    params_.fail("", "strength reduction needs block bodies (the slope's blocks and its fixed base)");
  const BlockSet& b = *world.blocks;
  std::size_t free_blocks = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const ParamValues& body = world.bodies[b.body[i]].params;
    if (b.kinematic[i])
      body.fail("motion", "block '" + b.name[i] + "' has a prescribed motion; strength reduction loads the slope "
                          "by gravity alone");
    if (!b.fixed[i]) ++free_blocks;
  }
  if (free_blocks == 0) params_.fail("", "every block is fixed: there is nothing that could slide");
  const dda::ContactSet& c = dda_->contacts();
  if (c.size() == 0)
    params_.fail("", "no joints: no two blocks touch at the start (the slope's blocks must rest on each other "
                     "and on the fixed base)");
  // Counted per rigid body: a clump's block may rest on its clump alone.
  const std::vector<std::uint32_t>& body = dda_->rigid_body();
  std::vector<std::uint32_t> touching(b.size(), 0);
  const double margin = dda_->contact_margin();
  for (std::size_t k = 0; k < c.size(); ++k) {
    ++touching[body[c.key[k].a]];
    ++touching[body[c.key[k].b]];
    if (c.gap[k] < -margin)
      world.bodies[b.body[c.key[k].b]].params.fail(
          "shape", "blocks '" + b.name[c.key[k].a] + "' and '" + b.name[c.key[k].b] + "' overlap by " +
                       number("%.3g", -c.gap[k]) + " m at the start (more than the contact margin " +
                       number("%.3g", margin) + " m); the slope's blocks must fit without overlap");
  }
  for (std::size_t i = 0; i < b.size(); ++i)
    if (!b.fixed[i] && touching[body[i]] == 0)
      world.bodies[b.body[i]].params.fail("shape", "block '" + b.name[i] + "' touches no other block at the "
                                                   "start: it would fall freely");
}

void StrengthReduction::locate_monitors(const World& world) {
  const BlockSet& b = *world.blocks;
  const std::vector<Vec3> points = params_.vectors("monitors");
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec3 p = points[k];
    bool found = false;
    for (std::size_t i = 0; i < b.size() && !found; ++i) {
      const Vec3 body_point = rotate_inverse(b.orientation[i], p - b.position[i]);
      if (!inside(b.shape[i], body_point)) continue;
      if (b.fixed[i])
        throw InputError("error: " + params_.file() + ": " + params_.pointer("monitors") + "/" + std::to_string(k) +
                         ": the monitor point lies in the fixed block '" + b.name[i] + "'; it never moves");
      monitors_.push_back({static_cast<std::uint32_t>(i), body_point, p});
      found = true;
    }
    if (!found)
      throw InputError("error: " + params_.file() + ": " + params_.pointer("monitors") + "/" + std::to_string(k) +
                       ": the monitor point [" + number("%g", p.x) + ", " + number("%g", p.y) + ", " +
                       number("%g", p.z) + "] lies outside every block");
  }
}

double StrengthReduction::stable_time_step(World& world) {
  if (loaded_ && !search_.searching()) return std::numeric_limits<double>::infinity();
  return world.end_time / trial_budget_;
}

double StrengthReduction::displacement(const BlockSet& b) const {
  double d = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (!b.fixed[i])
      d = std::max(d, norm(b.position[i] - loaded_position_[i]) +
                          b.shape[i].radius * rotation_angle(loaded_orientation_[i], b.orientation[i]));
  for (const Monitor& m : monitors_) d = std::max(d, norm(b.to_world(m.block, m.body_point) - m.start));
  return d;
}

TrialResult StrengthReduction::relax(World& world, double factor) {
  const auto t0 = std::chrono::steady_clock::now();
  for (auto& j : joints_) j->set_factor(factor, !loaded_);
  BlockSet& b = *world.blocks;
  TrialResult r;
  r.factor = factor;
  const double dissipated_before = b.energy.dissipated;
  double last = 0.0, last_increase = 0.0;
  int windows = 0, growing = 0;
  for (r.steps = 1;; ++r.steps) {
    dda_->relax_step(world);
    r.ratio = dda_->unbalanced_ratio();
    if (r.ratio < ratio_limit_) break;
    if (loaded_ && r.steps % window_ == 0) {
      const double d = displacement(b);
      if (d > displacement_limit_) {
        r.displaced = true;
        break;
      }
      const double increase = d - last;
      growing = windows > 0 && increase > 0.0 && increase >= 0.9 * last_increase ? growing + 1 : 0;
      if (growing >= 3) {
        r.growing = true;
        break;
      }
      last = d;
      last_increase = increase;
      ++windows;
    }
    if (r.steps >= max_steps_) {
      r.budget = true;
      break;
    }
  }
  // The gravity-loaded state is where displacements count from.
  r.monitors.assign(monitors_.size(), Vec3{});
  if (loaded_) {
    r.displacement = displacement(b);
    for (std::size_t k = 0; k < monitors_.size(); ++k)
      r.monitors[k] = b.to_world(monitors_[k].block, monitors_[k].body_point) - monitors_[k].start;
  }
  const dda::ContactSet& c = dda_->contacts();
  r.contacts = c.size();
  for (std::size_t k = 0; k < c.size(); ++k) {
    const auto s = c.state[k] & dda::contact_state_mask;
    r.open += s == dda::contact_open;
    r.stick += s == dda::contact_stick;
    r.slip += s == dda::contact_slip;
    r.bonded += (c.state[k] & dda::contact_bonded) != 0;
  }
  const Release release = released_blocks(b, c, dda_->rigid_body());
  r.released_blocks = release.blocks.size();
  r.released_mass = release.mass_fraction;
  r.slip_path = !release.blocks.empty();
  r.fails = fails(r);
  r.dissipated = b.energy.dissipated - dissipated_before;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void StrengthReduction::choose_window() {
  if (params_.has("window")) return;
  window_ = dda_->fixed_joints() ? std::max<std::int64_t>(default_window, log_.front().steps) : default_window;
}

bool StrengthReduction::fails(const TrialResult& r) const {
  return r.budget || r.displaced || r.growing || (by_slip_path_ && r.slip_path);
}

void StrengthReduction::restore_loaded_state(World& world) {
  dda_->load_state(loaded_dda_);
  BlockSet& b = *world.blocks;
  b.position = loaded_position_;
  b.orientation = loaded_orientation_;
  dda_->stop_blocks(world);
}

void StrengthReduction::advance(World& world, double /*dt*/) {
  BlockSet& b = *world.blocks;
  if (!loaded_) {
    TrialResult r = relax(world, elastic_factor);
    r.factor = std::numeric_limits<double>::infinity();
    if (r.budget)
      throw RunError("error: strength_reduction: the gravity-loaded state (joints far stronger than given) did "
                     "not reach equilibrium in " + std::to_string(max_steps_) + " steps (unbalanced-force ratio " +
                     number("%.3g", r.ratio) + " > " + number("%.3g", ratio_limit_) +
                     "); raise max_steps or check that every free block rests on others");
    loaded_dda_ = dda_->save_state();
    loaded_position_ = b.position;
    loaded_orientation_ = b.orientation;
    for (Monitor& m : monitors_) m.start = b.to_world(m.block, m.body_point);
    log_.push_back(r);
    loaded_ = true;
    choose_window();
    return;
  }
  if (!search_.searching()) return;
  restore_loaded_state(world);
  TrialResult r = relax(world, search_.next());
  (r.failed() ? failed_ : stable_) = capture(r, dda_->contacts(), b, loaded_position_, dda_->rigid_body());
  search_.record(r.failed());
  log_.push_back(std::move(r));
}

StagePlan StrengthReduction::plan(const World& world) const {
  StagePlan p = dda_->plan(world);
  p.notes.resize(std::min<std::size_t>(p.notes.size(), 1));  // the block count; the stage sets the host step itself
  p.passes.insert(p.passes.begin(), "per trial F: restore the gravity-loaded state, joints at c/F and tan(phi)/F");
  p.passes.push_back("local damping " + number("%g", damping_) + "; equilibrium at unbalanced-force ratio < " +
                     number("%g", ratio_limit_) + ", at most " + std::to_string(max_steps_) + " steps");
  p.notes.push_back("bracket [" + number("%g", search_.lo()) + ", " + number("%g", search_.hi()) +
                    "], tolerance " + number("%g", tolerance_) + ": at most " + std::to_string(trial_budget_) +
                    " host steps (the gravity-loaded state and one trial each)");
  p.notes.push_back(std::to_string(monitors_.size()) + " monitor point(s)");
  return p;
}

std::string StrengthReduction::status(const World& /*world*/) const {
  if (log_.empty()) return "relaxing the gravity-loaded state";
  const TrialResult& t = log_.back();
  std::string s = std::isinf(t.factor) ? "gravity-loaded state"
                                       : "trial " + std::to_string(log_.size() - 1) + " F = " + number("%.4f", t.factor);
  s += ": " + outcome(t) + " (" + std::to_string(t.steps) + " steps, ratio " + number("%.2g", t.ratio) + ")";
  if (search_.phase() == FactorSearch::Phase::bisect || search_.phase() == FactorSearch::Phase::done)
    s += "; F_s in [" + number("%.4f", search_.lo()) + ", " + number("%.4f", search_.hi()) + "]";
  return s;
}

std::string StrengthReduction::save_state() const {
  StateWriter w;
  w.value(search_);
  w.value(static_cast<std::uint8_t>(loaded_));
  w.bytes(loaded_dda_);
  w.vector(loaded_position_);
  w.vector(loaded_orientation_);
  std::vector<Vec3> starts;
  for (const Monitor& m : monitors_) starts.push_back(m.start);
  w.vector(starts);
  w.value<std::uint64_t>(log_.size());
  for (const TrialResult& t : log_) archive_trial(w, const_cast<TrialResult&>(t));
  archive_limit_state(w, const_cast<LimitState&>(stable_));
  archive_limit_state(w, const_cast<LimitState&>(failed_));
  w.bytes(dda_->save_state());
  return std::move(w.out);
}

void StrengthReduction::load_state(std::string_view bytes) {
  StateReader r{bytes, "the strength_reduction stage's state"};
  FactorSearch search;
  r.value(search);
  if (search.tolerance() != search_.tolerance())
    throw InputError("error: checkpoint: its strength-reduction search has another tolerance than this scene's");
  search_ = search;
  std::uint8_t loaded = 0;
  r.value(loaded);
  loaded_ = loaded != 0;
  r.bytes(loaded_dda_);
  r.vector(loaded_position_);
  r.vector(loaded_orientation_);
  std::vector<Vec3> starts;
  r.vector(starts);
  if (starts.size() != monitors_.size())
    throw InputError("error: checkpoint: it has " + std::to_string(starts.size()) + " monitor points, this scene " +
                     std::to_string(monitors_.size()));
  for (std::size_t k = 0; k < starts.size(); ++k) monitors_[k].start = starts[k];
  std::uint64_t trials = 0;
  r.value(trials);
  if (trials > static_cast<std::uint64_t>(trial_budget_))
    throw InputError("error: checkpoint: it records " + std::to_string(trials) + " strength-reduction trials, more "
                     "than this scene's search takes");
  log_.assign(trials, {});
  for (TrialResult& t : log_) {
    archive_trial(r, t);
    t.fails = fails(t);
  }
  if (!log_.empty()) choose_window();
  archive_limit_state(r, stable_);
  archive_limit_state(r, failed_);
  std::string dda_state;
  r.bytes(dda_state);
  r.finish();
  dda_->load_state(dda_state);
}

std::vector<std::string> StrengthReduction::finish(World& world, const std::string& output_directory) {
  const std::string csv = writers::join_path(output_directory, file_ + ".csv");
  std::string table = csv_header(monitors_.size());
  for (std::size_t k = 0; k < log_.size(); ++k) table += csv_row(k, log_[k]);
  writers::write_whole_file(csv + ".tmp", table);
  writers::publish(csv + ".tmp", csv, false);
  // With collapse deciding, the failing mass is the one that moved, whether or not a slip path bounds it.
  const bool by_motion = !by_slip_path_ && search_.phase() == FactorSearch::Phase::done && failed_.present &&
                         stable_.present && world.blocks;
  const double held = by_motion ? release_moved_blocks(failed_, stable_) : 0.0;
  const std::string h5 = writers::join_path(output_directory, file_ + "_limit_state.h5");
  if (world.blocks) write_limit_state(h5, *world.blocks, stable_, failed_);

  std::int64_t steps = 0;
  double wall = 0.0;
  for (const TrialResult& t : log_) {
    steps += t.steps;
    wall += t.wall_seconds;
  }
  const std::string cost = std::to_string(log_.size()) + " relaxations, " + std::to_string(steps) + " steps, " +
                           number("%.3g", wall) + " s";
  const std::string lo = number("%.4f", search_.lo()), hi = number("%.4f", search_.hi());
  using Phase = FactorSearch::Phase;
  if (search_.phase() == Phase::fails_at_lower)
    throw RunError("error: strength_reduction: the slope fails already at F = " + lo + ", so F_s < " + lo +
                   "; lower bracket[0] (" + params_.pointer("bracket") + "/0). Trials: " + csv);
  if (search_.phase() == Phase::holds_at_upper)
    throw RunError("error: strength_reduction: the slope still holds at F = " + hi + ", so F_s > " + hi +
                   "; raise bracket[1] (" + params_.pointer("bracket") + "/1). Trials: " + csv);
  std::vector<std::string> lines;
  for (std::size_t k = 0; k < log_.size(); ++k) {
    const TrialResult& t = log_[k];
    double monitor = 0.0;
    for (const Vec3& d : t.monitors) monitor = std::max(monitor, norm(d));
    lines.push_back("strength_reduction: trial " + std::to_string(k) + " F = " +
                    (std::isinf(t.factor) ? std::string("elastic") : number("%.4f", t.factor)) + ": " + outcome(t) +
                    "; " + std::to_string(t.steps) + " steps, ratio " + number("%.2g", t.ratio) + "; contacts " +
                    std::to_string(t.open) + " open, " + std::to_string(t.stick) + " closed, " +
                    std::to_string(t.slip) + " slip; displacement " + number("%.3g", t.displacement) + " m" +
                    (t.monitors.empty() ? "" : ", monitors up to " + number("%.3g", monitor) + " m") + "; " +
                    number("%.3g", t.wall_seconds) + " s");
  }
  if (search_.phase() == Phase::done) {
    lines.push_back("strength_reduction: F_s = " + number("%.4f", search_.safety_factor()) + " (holds at " + lo +
                    ", fails at " + hi + "; tolerance " + number("%g", tolerance_) + "; " + cost + ")");
    if (failed_.present) {
      const TrialResult& f = *std::find_if(log_.rbegin(), log_.rend(), [&](const TrialResult& t) {
        return t.factor == failed_.factor;
      });
      lines.push_back("strength_reduction: at F = " + hi + ": " + outcome(f) + "; " + std::to_string(f.slip) + " of " +
                      std::to_string(f.contacts) + " contacts slip, " + std::to_string(f.released_blocks) +
                      " block(s) released (" + number("%.3g", 100.0 * f.released_mass) + " % of the free mass)");
    }
    if (by_motion) {
      const BlockSet& b = *world.blocks;
      std::size_t moved = 0;
      double moved_mass = 0.0, free_mass = 0.0;
      for (std::size_t i = 0; i < b.size(); ++i) {
        if (b.fixed[i]) continue;
        free_mass += b.mass[i];
        if (failed_.released[i]) {
          ++moved;
          moved_mass += b.mass[i];
        }
      }
      lines.push_back("strength_reduction: the failing mass: " + std::to_string(moved) + " block(s) (" +
                      number("%.3g", 100.0 * moved_mass / free_mass) + " % of the free mass) moved farther at F = " +
                      hi + " than any block at F = " + lo + " (" + number("%.3g", held) + " m); the limit state and "
                      "the hand-off take them as released");
    }
  } else {
    lines.push_back("strength_reduction: the run ended before the search did (" + cost + "); F_s not found");
  }
  lines.push_back("strength_reduction: trials in " + csv + ", limit state in " + h5);
  if (handoff_ && search_.phase() == Phase::done)
    for (auto& line : write_handoff(world, output_directory)) lines.push_back(std::move(line));
  return lines;
}

std::vector<std::string> StrengthReduction::write_handoff(const World& world, const std::string& out) const {
  const BlockSet& b = *world.blocks;
  std::vector<std::uint8_t> released = failed_.released;
  if (std::find(released.begin(), released.end(), 1) == released.end())
    return {"strength_reduction: hand-off: no block is released at F = " + number("%.4f", search_.hi()) +
            " (it failed by the other criteria); nothing to hand off"};
  runout::Grid layout;
  if (has_dem_) {
    layout = dem_;
  } else {
    Vec3 lo{1e300, 1e300, 0.0}, hi{-1e300, -1e300, 0.0};
    for (std::size_t i = 0; i < b.size(); ++i)
      for (const Vec3& v : b.shape[i].vertices) {
        const Vec3 x = loaded_position_[i] + rotate(loaded_orientation_[i], v);
        lo = {std::min(lo.x, x.x), std::min(lo.y, x.y), 0.0};
        hi = {std::max(hi.x, x.x), std::max(hi.y, x.y), 0.0};
      }
    const double cell = handoff_cell_, m = handoff_margin_;
    layout.cell = cell;
    layout.x0 = lo.x - m + 0.5 * cell;
    layout.y0 = lo.y - m + 0.5 * cell;
    layout.resize(std::max(2, static_cast<int>(std::ceil((hi.x - lo.x + 2 * m) / cell - 1e-9))),
                  std::max(2, static_cast<int>(std::ceil((hi.y - lo.y + 2 * m) / cell - 1e-9))), 0.0);
  }
  const Handoff h = build_handoff(b, loaded_position_, loaded_orientation_, released, stable_, layout,
                                  has_dem_ ? &dem_ : nullptr, basal_shear_);
  const auto [joint, joint_share] = slip_surface_joint(stable_, released, b.body, joint_of_body_);
  const double fs = search_.safety_factor();
  const double cohesion = joint ? joint->base().cohesion / fs : 0.0;
  const double tan_friction = joint ? joint->base().tan_friction / fs : 0.0;
  const std::string prefix = file_;
  runout::write_esri_ascii(writers::join_path(out, prefix + "_terrain.asc"), h.terrain, 9);
  runout::write_esri_ascii(writers::join_path(out, prefix + "_thickness.asc"), h.thickness, 9);
  runout::write_esri_ascii(writers::join_path(out, prefix + "_basal_shear.asc"), h.basal_shear, 9);
  const std::string scene_path = writers::join_path(out, prefix + "_runout.json");
  const std::string description =
      "Run-out of the blocks that fail at F_s = " + number("%.4f", fs) + " in " + params_.file() +
      ", written by its strength_reduction stage from " + runout_template_.path + ": terrain " + prefix +
      "_terrain.asc (blocks that hold, then the DEM), vertical release thickness " + prefix +
      "_thickness.asc, limit-state basal shear " + prefix + "_basal_shear.asc, joint strength reduced by F_s.";
  const std::string text = runout_scene(runout_template_, h, prefix, cohesion, tan_friction, description).dump(2);
  writers::write_whole_file(scene_path + ".tmp", text + "\n");
  writers::publish(scene_path + ".tmp", scene_path, false);
  return {"strength_reduction: hand-off: released volume " + number("%.6g", h.failed_volume) + " m^3, in the "
          "thickness raster " + number("%.6g", h.raster_volume) + " m^3 (" +
              number("%+.3f", 100.0 * (h.raster_volume / h.failed_volume - 1.0)) + " %); basal shear from " +
              std::to_string(h.slip_contacts) + " slip-surface contacts (" +
              (basal_shear_ == BasalShear::inverse_distance_linear ? "inverse distance, linear nodal functions"
                                                                   : "inverse distance") +
              "); c/F_s = " + number("%.4g", cohesion) +
              " Pa, phi_F = " + number("%.4g", std::atan(tan_friction) * 180.0 / std::numbers::pi) +
              " deg (the joint under " + number("%.3g", 100.0 * joint_share) + " % of the slip surface's area)",
          "strength_reduction: run-out scene " + scene_path + " (run it: talus run " + scene_path + ")"};
}

}  // namespace talus::strength_reduction
