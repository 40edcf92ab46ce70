#include "wcsph_stage.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "fluid_fields.hpp"
#include "talus/eos.hpp"
#include "talus/error.hpp"
#include "talus/periodic.hpp"
#include "talus/rheology.hpp"
#include "talus/world.hpp"

namespace talus::wcsph {

ParamSet WcsphStage::describe() {
  ParamSet p{"wcsph", "weakly compressible SPH for water, 2D and 3D (coastline seed; DualSPHysics formulation)"};
  p.choice("integrator", {"symplectic", "verlet", "predictor_corrector", "euler"})
      .default_value("symplectic")
      .doc("time integration: symplectic (2 evaluations/step), verlet (1), predictor_corrector (2), euler (1)");
  p.integer("verlet_steps").min(1).default_value(40).doc("verlet: a corrective Euler step every this many steps");
  p.real("courant").greater_than(0.0).max(1.0).default_value(0.2).doc(
      "Courant number C in dt = C min(sqrt(h/|f|), h/(c + h visc), h^2/nu)");
  p.choice("viscosity", {"artificial", "laminar", "laplacian"})
      .default_value("artificial")
      .doc("artificial (Monaghan, alpha), laminar (Morris/Lo-Shao, material's Newtonian viscosity) or laplacian "
           "(rock-fluid seed eq. 18, needs the muller kernel)");
  p.real("alpha").min(0.0).default_value(0.01).doc("artificial viscosity coefficient");
  p.choice("density", {"continuity", "summation"})
      .default_value("continuity")
      .doc("density from the continuity equation or by summation rho_i = sum m_j W_ij");
  p.choice("density_diffusion", {"none", "molteni", "fourtakas"})
      .default_value("fourtakas")
      .doc("delta-SPH density diffusion (continuity only): Molteni-Colagrossi 2009 or Fourtakas et al. 2019");
  p.real("delta").min(0.0).default_value(0.1).doc("density diffusion coefficient delta");
  p.choice("turbulence", {"none", "smagorinsky"})
      .default_value("none")
      .doc("laminar only, or the Smagorinsky (SPS) eddy viscosity rho (Cs dp)^2 |S| added to the laminar one");
  p.real("smagorinsky_cs").greater_than(0.0).max(1.0).default_value(0.12)
      .doc("Smagorinsky constant Cs (DualSPHysics/Dalrymple & Rogers 2006: 0.12)");
  p.choice("viscosity_mean", {"arithmetic", "harmonic"})
      .default_value("arithmetic")
      .doc("pair viscosity from mu_eff of both particles (non-Newtonian/turbulent): arithmetic mu_i + mu_j "
           "(Morris 1997) or harmonic 4 mu_i mu_j/(mu_i + mu_j) (Cleary 1998; for viscosity jumps)");
  p.choice("stiff_viscosity", {"explicit", "point_implicit"})
      .default_value("explicit")
      .doc("explicit: the viscous step dt <= C h^2 rho/mu_eff; point_implicit: each particle's momentum change is "
           "divided by 1 + dt D_i (D_i its viscous coupling, the diagonal of a backward-Euler viscous step), which "
           "removes that bound and keeps equilibria (a local mass scaling): for plug regions that should stay at "
           "rest (an unyielded sediment core); a plug that must accelerate as a whole does so ~dt D times too slowly "
           "(Bingham channel spin-up); needs mu_eff (laminar, non-Newtonian) and viscosity_mean harmonic");
  return p;
}

namespace {
template <class E>
E pick(const ParamValues& v, const char* name, std::initializer_list<std::pair<const char*, E>> table) {
  const std::string& s = v.string(name);
  for (const auto& [key, value] : table)
    if (s == key) return value;
  v.fail(name, "unknown value '" + s + "'");
}
}  // namespace

WcsphStage::WcsphStage(const ParamValues& v)
    : integrator_(pick<Integrator>(v, "integrator",
                                   {{"symplectic", Integrator::symplectic},
                                    {"verlet", Integrator::verlet},
                                    {"predictor_corrector", Integrator::predictor_corrector},
                                    {"euler", Integrator::euler}})),
      verlet_steps_(static_cast<int>(v.integer("verlet_steps"))),
      courant_(v.real("courant")),
      viscosity_(pick<ViscosityModel>(v, "viscosity",
                                           {{"artificial", ViscosityModel::artificial},
                                            {"laminar", ViscosityModel::laminar},
                                            {"laplacian", ViscosityModel::laplacian}})),
      alpha_(v.real("alpha")),
      density_(pick<DensityMode>(v, "density",
                                 {{"continuity", DensityMode::continuity}, {"summation", DensityMode::summation}})),
      diffusion_(pick<Diffusion>(v, "density_diffusion",
                                 {{"none", Diffusion::none},
                                  {"molteni", Diffusion::molteni},
                                  {"fourtakas", Diffusion::fourtakas}})),
      delta_(v.real("delta")),
      smagorinsky_(v.string("turbulence") == "smagorinsky"),
      smagorinsky_cs_(v.real("smagorinsky_cs")),
      viscosity_mean_(pick<sph::ViscosityMean>(v, "viscosity_mean",
                                               {{"arithmetic", sph::ViscosityMean::arithmetic},
                                                {"harmonic", sph::ViscosityMean::harmonic}})),
      params_(v),
      point_implicit_(v.string("stiff_viscosity") == "point_implicit") {}

void WcsphStage::setup(World& world) {
  h_ = world.kernel.h();
  if (!(h_ > 0.0)) params_.fail("", "the wcsph stage needs a smoothing kernel: add \"kernel\": {\"type\": ...} to the scene");
  if (viscosity_ == ViscosityModel::laplacian && !world.kernel.has_laplacian())
    params_.fail("viscosity", "'laplacian' needs a kernel with a Laplacian; allowed with kernel 'muller'");

  ParticleStore& s = world.fluid;
  const bool single = single_fluid_allowed(world);
  for (const FieldInfo* info : fluid_fields_in_float) {
    FieldInfo field = *info;
    field.single_when_mixed = single;
    s.require(field);
  }
  keep_fluid_fields_alike(s);
  if (integrator_ == Integrator::symplectic || integrator_ == Integrator::predictor_corrector)
    for (const FieldInfo* info : {&field_position_n, &field_velocity_n, &field_density_n}) s.require(*info);
  if (integrator_ == Integrator::verlet)
    for (const FieldInfo* info : {&field_velocity_prev, &field_density_prev}) s.require(*info);

  // Materials: every fluid particle's material needs an EOS; laminar
  // viscosity needs a Newtonian rheology.
  const std::size_t nm = world.materials.size();
  material_mu_.assign(std::max<std::size_t>(nm, 1), 0.0);
  material_rho0_.assign(std::max<std::size_t>(nm, 1), 0.0);
  std::vector<char> used(nm, 0);
  for (std::int32_t m : s.material()) {
    if (m < 0 || static_cast<std::size_t>(m) >= nm)
      params_.fail("", "a fluid particle has no material; every fluid body needs \"material\"");
    used[m] = 1;
  }
  fluid_materials_.clear();
  rheology_materials_.clear();
  c0_max_ = 0.0;
  nu_max_ = 0.0;
  for (std::size_t m = 0; m < nm; ++m) {
    const Material& mat = world.materials[m];
    material_rho0_[m] = mat.density;
    // Non-Newtonian materials: the reference viscosity stands for mu_eff where
    // a per-particle value is not available (walls that ignore FluidView::viscosity).
    if (mat.rheology) material_mu_[m] = mat.rheology->reference_viscosity();
    if (!used[m]) continue;
    if (!mat.eos)
      mat.params.fail("eos", "material '" + mat.name + "' is used by fluid particles but has no equation of state");
    const bool newtonian = mat.rheology && mat.rheology->is_newtonian();
    if (viscosity_ == ViscosityModel::laplacian && !newtonian)
      mat.params.fail("rheology", "viscosity 'laplacian' of stage wcsph needs a Newtonian rheology for material '" +
                                      mat.name + "'; allowed: {\"type\": \"newtonian\", \"viscosity\": ...}, or "
                                      "viscosity 'laminar' for non-Newtonian rheologies");
    if (viscosity_ == ViscosityModel::laminar && !newtonian) {
      if (!mat.rheology || !mat.rheology->has_apparent_viscosity())
        mat.params.fail("rheology", "viscosity 'laminar' of stage wcsph needs a rheology with an apparent viscosity "
                                    "for material '" + mat.name + "'; allowed: newtonian, bingham, hbp, power_law, "
                                    "herschel_bulkley");
      rheology_materials_.push_back(static_cast<int>(m));
    }
    fluid_materials_.push_back(static_cast<int>(m));
    c0_max_ = std::max(c0_max_, mat.eos->reference_sound_speed());
    if (viscosity_ != ViscosityModel::artificial && mat.density > 0.0)
      nu_max_ = std::max(nu_max_, material_mu_[m] / mat.density);
  }

  // Three-pass viscosity only where something makes mu_eff vary per particle.
  if (smagorinsky_ && viscosity_ != ViscosityModel::laminar)
    params_.fail("turbulence", "'smagorinsky' adds to the laminar viscosity; needs \"viscosity\": \"laminar\"");
  per_particle_viscosity_ = viscosity_ == ViscosityModel::laminar && (smagorinsky_ || !rheology_materials_.empty());
  if (per_particle_viscosity_) {
    s.require(field_shear_rate);
    s.require(field_mu_eff);
  }
  nu_field_max_ = 0.0;
  if (point_implicit_) {
    if (!per_particle_viscosity_ || viscosity_mean_ != sph::ViscosityMean::harmonic)
      params_.fail("stiff_viscosity", "'point_implicit' needs \"viscosity\": \"laminar\" with a non-Newtonian "
                                      "rheology and \"viscosity_mean\": \"harmonic\"; allowed: explicit");
    bulk_viscous_support_ = lattice_viscous_support(world);
  }

  // Boundary models of walls (and of blocks, for fluid-block coupling): each
  // must be an SPH boundary pass; one pass per model instance.
  walls_.clear();
  for (const Body& body : world.bodies) {
    if (!body.boundary) continue;
    auto* wall = dynamic_cast<sph::SphBoundary*>(body.boundary);
    if (!wall)
      body.params.fail("boundary", "the boundary model of body '" + body.name +
                                       "' is not an SPH boundary pass and does not work with stage wcsph");
    if (std::find(walls_.begin(), walls_.end(), wall) == walls_.end()) walls_.push_back(wall);
  }

  // The fluid's neighbour grid covers the domain plus a margin for particles about
  // to be removed; periodic axes use the period exactly.
  const double radius = world.kernel.support_radius();
  Vec3 lo = world.lo, hi = world.hi;
  for (int a = 0; a < world.dim; ++a)
    if (!world.periodic[a]) {
      lo[a] -= radius;
      hi[a] += radius;
    }
  cells_.configure(world.dim, lo, hi, radius, world.periodic);

  settings_ = sph::FluidSettings{&world.kernel, density_ == DensityMode::summation, lo, hi,
                                 viscosity_ != ViscosityModel::artificial, &cells_};
  period_ = periods(world);
  pair_terms_ = world.pair_terms;
  for (sph::PairTerm* term : pair_terms_) term->setup(world);
  world.pair_terms_run = true;
  world.refresh_material_index();
  update_pressure(world);
  // Rebuilt for each model: one may remove or move fluid particles as it binds (blocks).
  for (sph::SphBoundary* wall : walls_) {
    cells_.build(world.fluid.position());
    wall->bind(world, settings_);
  }

  if (integrator_ == Integrator::verlet)
    with_fluid_fields(s, [&](auto f) {
      s.visit_vector("velocity_prev", [&](auto v_prev) {
        std::ranges::transform(f.v, v_prev.begin(), [](Vec3 v) { return typename decltype(v_prev)::value_type(v); });
      });
      s.visit_scalar("density_prev", [&](auto rho_prev) {
        std::ranges::transform(f.rho, rho_prev.begin(), [](double rho) {
          return static_cast<typename decltype(rho_prev)::value_type>(rho);
        });
      });
    });
  verlet_counter_ = 0;
  rates_valid_ = false;
  worst_deviation_ = max_density_deviation(world);
  worst_deviation_time_ = world.time;
}

// The fluid's state and rates (fluid_fields_in_float) in float, in a scene
// of mixed precision where everything that reads the fluid reads float:
// every wall model says so (SphBoundary::reads_single_fluid), and there is
// no pair-term plugin (it sees the FluidView in double) and no three-pass
// viscosity (its passes and the rheologies' batch calls read double).
bool WcsphStage::single_fluid_allowed(const World& world) const {
  if (!world.fluid.mixed_precision() || !world.pair_terms.empty()) return false;
  if (viscosity_ == ViscosityModel::laminar) {
    if (smagorinsky_) return false;
    for (const Body& body : world.bodies) {
      if (body.kind != BodyKind::fluid || body.material < 0) continue;
      const Material& m = world.materials[body.material];
      if (m.rheology && !m.rheology->is_newtonian()) return false;
    }
  }
  for (const Body& body : world.bodies) {
    if (!body.boundary) continue;
    const auto* wall = dynamic_cast<const sph::SphBoundary*>(body.boundary);
    if (!wall || !wall->reads_single_fluid()) return false;
  }
  return true;
}

StageParts WcsphStage::parts(const World& world) const {
  StageParts parts{{}, {}, {"velocity", "density", "pressure", "mass"}};
  if (single_fluid_allowed(world)) parts.single_body_fields = parts.body_fields;
  for (const Body& body : world.bodies)
    if (body.kind == BodyKind::block && body.boundary) parts.needs = {"blocks"};
  return parts;
}

ViscositySettings WcsphStage::viscosity_settings(const World& world) const {
  return {viscosity_,           alpha_ * h_,     material_mu_.data(), sph::laminar_eta2(h_),
          per_particle_viscosity_, viscosity_mean_, &world.kernel};
}

bool WcsphStage::rates_current(const World& world) const {
  return rates_valid_ && rates_step_ == world.step && rates_time_ == world.time && rates_size_ == world.fluid.size();
}

double WcsphStage::stable_time_step(World& world) {
  // The rates at t^n are computed once, here, and reused by advance().
  if (!rates_current(world)) compute_rates(world);
  // The bound combines maxima that may sit on different ranks: each is taken over all of them.
  const std::size_t owned = world.fluid.owned_size();
  double a_max = 0.0, c_max = 0.0, visc_max = std::max(fluid_visc_max_, rates_visc_max_);
  with_fluid_fields(world.fluid, [&](auto f) {
#pragma omp parallel for schedule(static) reduction(max : a_max, c_max) if (owned >= 4096)
    for (std::size_t i = 0; i < owned; ++i) {
      a_max = std::max(a_max, norm2(f.a[i]));
      c_max = std::max(c_max, static_cast<double>(f.c[i]));
    }
  });
  const Parallel& ranks = world.parallel();
  a_max = std::sqrt(ranks.max(a_max));
  c_max = ranks.max(c_max);
  visc_max = ranks.max(visc_max);
  double dt = std::numeric_limits<double>::infinity();
  if (a_max > 0.0) dt = std::min(dt, std::sqrt(h_ / a_max));
  c_max = std::max(c_max, c0_max_);
  dt = std::min(dt, h_ / (c_max + h_ * visc_max));
  // max mu_eff/rho with three passes
  const double nu_max = per_particle_viscosity_ ? ranks.max(nu_field_max_) : nu_max_;
  if (nu_max > 0.0) dt = std::min(dt, h_ * h_ / nu_max);
  dt *= courant_;
  for (const sph::SphBoundary* wall : walls_) dt = std::min(dt, wall->stable_time_step(world));
  for (const sph::PairTerm* term : pair_terms_) dt = std::min(dt, term->stable_time_step(world));
  return dt;
}

void WcsphStage::advance(World& world, double dt) {
  // On several ranks one with no fluid still takes part in the halo exchanges.
  if (world.fluid.size() == 0 && world.parallel().ranks() == 1) return;
  if (!rates_current(world)) compute_rates(world);
  switch (integrator_) {
    case Integrator::euler: step_euler(world, dt); break;
    case Integrator::verlet: step_verlet(world, dt); break;
    case Integrator::symplectic:
    case Integrator::predictor_corrector: step_two_stage(world, dt); break;
  }
  for (sph::SphBoundary* wall : walls_) wall->hold_fluid(world, world.time + dt);
  rates_valid_ = false;  // the state moved; the next step evaluates again
  const double deviation = world.parallel().max(max_density_deviation(world));  // every rank's worst
  if (deviation > worst_deviation_ || !std::isfinite(deviation)) {
    worst_deviation_ = deviation;
    worst_deviation_time_ = world.time + dt;
  }
}

double WcsphStage::max_density_deviation(const World& world) const {
  const auto mat = world.fluid.material();
  const std::size_t owned = world.fluid.owned_size();
  double dev = 0.0;
  world.fluid.visit_scalar("density", [&](auto rho) {
#pragma omp parallel for schedule(static) reduction(max : dev) if (owned >= 4096)
    for (std::size_t i = 0; i < owned; ++i) {
      const double rho0 = material_rho0_[mat[i]];
      dev = std::max(dev, std::abs(rho[i] / rho0 - 1.0));
    }
  });
  return dev;
}

// Text "COUNTER WORST TIME" (hex floats: a restart continues bit-for-bit); a
// checkpoint holding only the counter (older runs) keeps the setup's worst value.
std::string WcsphStage::save_state() const {
  char text[96];
  std::snprintf(text, sizeof text, "%llu %a %a", static_cast<unsigned long long>(verlet_counter_), worst_deviation_,
                worst_deviation_time_);
  return text;
}

void WcsphStage::load_state(std::string_view bytes) {
  // "COUNTER WORST WHEN", as save_state writes it, and nothing else.
  const std::string text(bytes);
  auto unreadable = [&](const char* why) {
    throw InputError("error: checkpoint: the wcsph stage's state '" + text + "' is not readable: " + why);
  };
  const char* p = text.c_str();
  char* end = nullptr;
  errno = 0;
  if (text.empty() || !std::isdigit(static_cast<unsigned char>(*p))) unreadable("no step counter");
  const unsigned long long counter = std::strtoull(p, &end, 10);
  if (errno == ERANGE) unreadable("the step counter is out of range");
  char* after = nullptr;
  const double worst = std::strtod(end, &after);
  if (after == end) unreadable("no worst density deviation");
  const double when = std::strtod(after, &end);
  if (end == after) unreadable("no time of the worst deviation");
  if (*end != '\0') unreadable("trailing characters");
  if (!std::isfinite(worst) || worst < 0.0 || !std::isfinite(when) || when < 0.0)
    unreadable("the worst density deviation and its time must be finite and >= 0");
  verlet_counter_ = counter;
  worst_deviation_ = worst;
  worst_deviation_time_ = when;
}

std::string WcsphStage::status(const World& world) const {
  char line[128];
  std::snprintf(line, sizeof line, "rho dev %.3g%% (worst %.3g%% at t = %.4g s)", 100.0 * max_density_deviation(world),
                100.0 * worst_deviation_, worst_deviation_time_);
  return line;
}

StagePlan WcsphStage::plan(const World& world) const {
  StagePlan plan;
  const char* visc = per_particle_viscosity_
                         ? (viscosity_mean_ == sph::ViscosityMean::harmonic
                                ? "laminar viscosity (Morris, mu_eff, harmonic mean)"
                                : "laminar viscosity (Morris, mu_eff, arithmetic mean)")
                     : viscosity_ == ViscosityModel::artificial ? "artificial viscosity"
                     : viscosity_ == ViscosityModel::laminar    ? "laminar viscosity (Morris)"
                                                                     : "Laplacian-kernel viscosity";
  std::string force = std::string("fluid-fluid pass: pressure + ") + visc;
  if (density_ == DensityMode::continuity) {
    force += " + continuity";
    if (diffusion_ == Diffusion::molteni) force += " + density diffusion (Molteni)";
    if (diffusion_ == Diffusion::fourtakas) force += " + density diffusion (Fourtakas)";
  }
  if (density_ == DensityMode::summation) plan.passes.push_back("fluid-fluid pass: summation density");
  plan.passes.push_back("EOS: one batch call per material");
  if (per_particle_viscosity_) {
    plan.passes.push_back("fluid-fluid pass: velocity gradient (Bonet-Lok corrected) -> shear_rate");
    std::string batch = "rheology: one apparent_viscosity batch call per non-Newtonian material -> mu_eff";
    if (smagorinsky_) batch += " + Smagorinsky eddy viscosity";
    plan.passes.push_back(batch);
  }
  if (point_implicit_) plan.notes.push_back("stiff_viscosity: point-implicit viscous inertia 1 + dt D_i per particle");
  plan.passes.push_back(force);
  for (const sph::SphBoundary* wall : walls_) wall->describe_passes(plan);
  for (const sph::PairTerm* term : pair_terms_) plan.passes.push_back("pair term pass: " + term->pass_description());
  const char* integ = integrator_ == Integrator::symplectic            ? "symplectic (2 evaluations per step)"
                      : integrator_ == Integrator::verlet              ? "Verlet (1 evaluation per step)"
                      : integrator_ == Integrator::predictor_corrector ? "predictor-corrector (2 evaluations per step)"
                                                                       : "explicit Euler (1 evaluation per step)";
  plan.notes.push_back(std::string("integrator: ") + integ);
  plan.reads = {"position", "velocity", "density", "mass", "material"};
  plan.writes = {"position", "velocity", "density", "pressure", "sound_speed", "acceleration", "density_rate"};
  if (per_particle_viscosity_) {
    plan.writes.push_back("shear_rate");
    plan.writes.push_back("mu_eff");
  }
  (void)world;
  return plan;
}

}  // namespace talus::wcsph
