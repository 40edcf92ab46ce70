// Building the world from the scene: materials, the smoothing kernel, the
// bodies and their particles, the pipeline of stages and the writers. Every
// setup check runs here, before anything is written.
#include "simulation.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "talus/number_text.hpp"
#include "plugin_registry.hpp"
#include "talus/boundary.hpp"
#include "talus/eos.hpp"
#include "talus/error.hpp"
#include "talus/geometry.hpp"
#include "talus/hydrostatic.hpp"
#include "talus/rheology.hpp"
#include "talus/smoothing_kernel.hpp"
#include "talus/sph/pair_term.hpp"
#include "talus/stage.hpp"
#include "talus/writer.hpp"
#include "text.hpp"

namespace talus {

void Simulation::build_materials() {
  const ParamValues& s = scene_.values;
  if (!s.has("materials")) return;
  const auto& names = s.keys("materials");
  const auto& entries = s.objects("materials");
  for (std::size_t i = 0; i < names.size(); ++i) {
    Material m;
    m.name = names[i];
    m.params = entries[i];
    m.density = entries[i].real("density");
    if (entries[i].has("eos")) {
      auto eos = registry_.create_as<EquationOfState>("eos", entries[i].model_name("eos"), entries[i].model_params("eos"));
      eos->set_reference_density(m.density);
      m.eos = eos.get();
      models_.push_back(std::move(eos));
    }
    if (entries[i].has("rheology")) {
      auto r = registry_.create_as<Rheology>("rheology", entries[i].model_name("rheology"),
                                             entries[i].model_params("rheology"));
      m.rheology = r.get();
      models_.push_back(std::move(r));
    }
    world_.materials.push_back(std::move(m));
  }
}

void Simulation::build_kernel() {
  const ParamValues& s = scene_.values;
  double dp_fluid = 0.0, dp_any = 0.0;
  for (const auto& b : s.objects("bodies")) {
    if (!b.has("dp")) continue;
    const double dp = b.real("dp");
    dp_any = dp_any > 0 ? std::min(dp_any, dp) : dp;
    if (b.string("kind") == "fluid") dp_fluid = dp_fluid > 0 ? std::min(dp_fluid, dp) : dp;
  }
  world_.dp = dp_fluid > 0 ? dp_fluid : dp_any;
  if (!s.has("kernel")) return;
  if (!(world_.dp > 0)) s.fail("kernel", "a smoothing kernel needs at least one fluid or wall body with a \"dp\"");
  kernel_name_ = s.model_name("kernel");
  const ParamValues& kp = s.model_params("kernel");
  auto kernel = registry_.create_as<SmoothingKernel>("kernel", kernel_name_, kp);
  world_.h = kp.real("h_over_dp") * world_.dp;
  // The table scales by h^-(dim+2) (the Laplacian's normalisation): beyond a
  // double's range it would hold zeros or infinities, or refuse h outright.
  const double scale = std::pow(world_.h, world_.dim + 2);
  if (!std::isnormal(scale) || !std::isfinite(1.0 / scale))
    s.fail("kernel", "the smoothing length h = h_over_dp x dp = " + fixed(world_.h) + " m (dp = " + fixed(world_.dp) +
                         " m) is beyond what a kernel table holds; use a dp between 1e-50 and 1e50 m");
  world_.kernel = KernelTable(*kernel, world_.dim, world_.h);
  models_.push_back(std::move(kernel));
}

// A periodic axis must span at least 2.5 kernel supports. The neighbour grid
// reports every image on any period, but the SPH stages and wall models are
// verified only where a particle meets one image of each neighbour, so a
// narrower axis is refused rather than run unverified; checked once here,
// with the scene's pointer.
void Simulation::check_periodic_axes() const {
  const ParamValues& domain = scene_.values.object("domain");
  const auto& axes = domain.strings("periodic");
  for (std::size_t k = 0; k < axes.size(); ++k) {
    auto fail = [&](const std::string& message) {
      throw InputError("error: " + domain.file() + ": " + domain.pointer("periodic") + "/" + std::to_string(k) + ": " +
                       message);
    };
    const int a = axes[k][0] - 'x';
    if (a >= world_.dim) fail(axes[k] + " is not an axis of a " + std::to_string(world_.dim) + "D domain");
    const double span = world_.hi[a] - world_.lo[a];
    const double support = world_.h > 0.0 ? world_.kernel.support_radius() : 0.0;
    if (support > 0.0 && !(span >= 2.5 * support))
      fail("the domain spans " + fixed(span) + " m along " + axes[k] +
           ", less than the 2.5 kernel supports a periodic axis needs (2.5 x " + fixed(support) +
           " m); enlarge the domain along it or refine dp");
  }
}

namespace {

// "hydrostatic": true: the bodies that ask for it start with the pressure of
// the fluid above them, every fluid body's weight included (talus/hydrostatic.hpp),
// and the density their equation of state gives at that pressure.
void start_hydrostatic(World& world, const std::vector<ParamValues>& bodies) {
  std::vector<char> hydrostatic(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b)
    hydrostatic[b] = bodies[b].string("kind") == "fluid" && bodies[b].boolean("hydrostatic");
  if (std::find(hydrostatic.begin(), hydrostatic.end(), 1) == hydrostatic.end()) return;
  ParticleStore& fluid = world.fluid;
  const auto body = fluid.body();
  const auto material = fluid.material();
  std::vector<double> spacing(fluid.size()), density(fluid.size());
  for (std::size_t i = 0; i < fluid.size(); ++i) {
    spacing[i] = world.bodies[body[i]].dp;
    density[i] = world.materials[material[i]].density;
  }
  const std::vector<double> p = hydrostatic_pressure(fluid.position(), spacing, density, world.gravity, world.dim);
  fluid.visit_scalar("pressure", [&](auto pressure) {
    for (std::size_t i = 0; i < fluid.size(); ++i)
      if (hydrostatic[body[i]]) pressure[i] = p[i];
  });
  fluid.visit_scalar("density", [&](auto rho) {
    for (std::size_t i = 0; i < fluid.size(); ++i)
      if (hydrostatic[body[i]]) rho[i] = world.materials[material[i]].eos->density_at(p[i]);
  });
}

}  // namespace

namespace {

bool same_values(const ParamValues& a, const ParamValues& b);

bool same_value(const ParamValue& a, const ParamValue& b) {
  if (a.type != b.type || a.real != b.real || a.integer != b.integer || a.boolean != b.boolean || a.text != b.text ||
      a.reals != b.reals || a.strings != b.strings || a.indices != b.indices || a.objects.size() != b.objects.size())
    return false;
  for (std::size_t k = 0; k < a.objects.size(); ++k)
    if (!same_values(a.objects[k], b.objects[k])) return false;
  return true;
}

// The same validated values (defaults filled), wherever in the scene they stand.
bool same_values(const ParamValues& a, const ParamValues& b) {
  const auto& x = a.entries();
  const auto& y = b.entries();
  if (x.size() != y.size()) return false;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (x[k].first != y[k].first || !same_value(x[k].second, y[k].second)) return false;
  return true;
}

}  // namespace

void Simulation::build_bodies() {
  const auto& bodies = scene_.values.objects("bodies");
  // Bodies that name the same boundary model with the same parameters share
  // one instance, set up once with all of them (Boundary::setup): a model
  // then holds every particle of its walls in one row range.
  std::vector<std::size_t> boundary_owner;  // the first body of each instance
  for (std::size_t bi = 0; bi < bodies.size(); ++bi) {
    const ParamValues& v = bodies[bi];
    Body body;
    body.name = v.string("name");
    body.params = v;
    const std::string& kind = v.string("kind");
    body.kind = kind == "fluid" ? BodyKind::fluid : (kind == "wall" ? BodyKind::wall : BodyKind::block);
    if (v.has("material")) body.material = world_.find_material(v.string("material"));
    if (v.has("dp")) body.dp = v.real("dp");
    if (v.has("boundary")) {  // walls, and blocks that the fluid sees
      auto same = [&](std::size_t owner) {
        const ParamValues& o = bodies[owner];
        return o.model_name("boundary") == v.model_name("boundary") &&
               same_values(o.model_params("boundary"), v.model_params("boundary"));
      };
      if (const auto it = std::ranges::find_if(boundary_owner, same); it != boundary_owner.end()) {
        body.boundary = world_.bodies[*it].boundary;
      } else {
        auto boundary = registry_.create_as<Boundary>("boundary", v.model_name("boundary"), v.model_params("boundary"));
        body.boundary = boundary.get();
        models_.push_back(std::move(boundary));
        boundary_owner.push_back(bi);
      }
    }
    if (v.has("contact")) {
      auto contact = registry_.create("contact", v.model_name("contact"), v.model_params("contact"));
      body.contact = contact.get();
      models_.push_back(std::move(contact));
    }
    world_.bodies.push_back(std::move(body));
  }
}

std::vector<Boundary*> Simulation::boundary_models() const {
  std::vector<Boundary*> models;
  for (const Body& body : world_.bodies)
    if (body.boundary && std::ranges::find(models, body.boundary) == models.end()) models.push_back(body.boundary);
  return models;
}

namespace {
// The fields of a fluid body's start state (StageParts::body_fields).
const FieldInfo kBodyFields[] = {{"velocity", FieldType::vector, "m/s", true, true},
                                 {"density", FieldType::scalar, "kg/m^3", true, true},
                                 {"pressure", FieldType::scalar, "Pa", true, true},
                                 {"mass", FieldType::scalar, "kg", true, true}};
}  // namespace

void Simulation::fill_bodies(const std::vector<FieldInfo>& fields) {
  const auto& bodies = scene_.values.objects("bodies");
  ParticleStore& fluid = world_.fluid;
  for (const FieldInfo& known : kBodyFields)  // in this order, whatever the stages' order
    if (const auto f = std::ranges::find(fields, known.name, &FieldInfo::name); f != fields.end()) fluid.require(*f);
  const bool velocity = fluid.has("velocity"), density = fluid.has("density"), pressure = fluid.has("pressure"),
             mass = fluid.has("mass");

  for (std::size_t bi = 0; bi < bodies.size(); ++bi) {
    const ParamValues& v = bodies[bi];
    Body& body = world_.bodies[bi];
    if (body.kind == BodyKind::fluid) {
      const Material& m = world_.materials[body.material];
      const std::string& alt = v.alternative("shape");
      const auto points = fill_points(alt, v.alternative_values("shape"), body.dp, world_.dim, world_.lo, world_.hi);
      // A shape must lie in the domain: the run would drop what is outside.
      auto outside = [&](const Vec3& q) {
        for (int a = 0; a < world_.dim; ++a)
          if (q[a] < world_.lo[a] || q[a] > world_.hi[a]) return true;
        return false;
      };
      if (points.empty()) v.fail("shape", "the shape holds no particle at dp = " + text::number(body.dp));
      if (const auto n_out = std::count_if(points.begin(), points.end(), outside))
        v.fail("shape", "fluid '" + body.name + "': " + std::to_string(n_out) + " of " + std::to_string(points.size()) +
                            " particles lie outside the domain " + vec_text(world_.lo, world_.dim) + " .. " +
                            vec_text(world_.hi, world_.dim) + "; shrink the shape or enlarge the domain");
      const std::size_t first = fluid.append(points.size());
      auto x = fluid.position();
      auto bid = fluid.body();
      auto mid = fluid.material();
      if (v.boolean("hydrostatic") && !m.eos)
        v.fail("hydrostatic", "needs the material '" + m.name + "' to have an \"eos\"");
      for (std::size_t k = 0; k < points.size(); ++k) {
        x[first + k] = points[k];
        bid[first + k] = static_cast<std::int32_t>(bi);
        mid[first + k] = body.material;
      }
      // Each field in the type it is stored in (float under mixed precision).
      auto fill_scalar = [&](const char* name, double value) {
        fluid.visit_scalar(name, [&](auto field) {
          std::fill(field.begin() + first, field.end(), static_cast<typename decltype(field)::value_type>(value));
        });
      };
      if (velocity)
        fluid.visit_vector("velocity", [&](auto field) {
          std::fill(field.begin() + first, field.end(), typename decltype(field)::value_type(v.vector("velocity")));
        });
      if (density) fill_scalar("density", m.density);
      if (pressure) fill_scalar("pressure", 0.0);
      const ParamValues& shape = v.alternative_values("shape");
      if (mass) fill_scalar("mass", m.density * lattice_volume(alt, shape, body.dp, world_.dim));
      if (const std::string adjusted = lattice_adjustment(alt, shape, body.dp, world_.dim); !adjusted.empty())
        world_.warnings.add("fluid '" + body.name + "' (" + v.pointer("shape") + "): " + adjusted);
    }
  }
  if (density && pressure) start_hydrostatic(world_, bodies);
  world_.refresh_material_index();
  // Each boundary model once, with all its bodies, in the order of its first.
  std::vector<Boundary*> done;
  for (const Body& first : world_.bodies) {
    if (!first.boundary || std::ranges::find(done, first.boundary) != done.end()) continue;
    std::vector<int> members;
    for (std::size_t bi = 0; bi < world_.bodies.size(); ++bi)
      if (world_.bodies[bi].boundary == first.boundary) members.push_back(static_cast<int>(bi));
    first.boundary->setup(world_, members);
    done.push_back(first.boundary);
  }
}

void Simulation::build_stages() {
  const ParamValues& s = scene_.values;
  const auto& term_names = s.model_names("pair_terms");
  const auto& term_params = s.objects("pair_terms");
  for (std::size_t i = 0; i < term_names.size(); ++i) {
    auto term = registry_.create_as<sph::PairTerm>("pair_term", term_names[i], term_params[i]);
    world_.pair_terms.push_back(term.get());
    models_.push_back(std::move(term));
  }
  const auto& names = s.model_names("pipeline");
  const auto& params = s.objects("pipeline");
  for (std::size_t i = 0; i < names.size(); ++i) {
    stages_.push_back(registry_.create_as<Stage>("stage", names[i], params[i]));
    stage_names_.push_back(names[i]);
  }
  fill_bodies(check_stage_parts());
  for (auto& stage : stages_) stage->setup(world_);
  if (!world_.pair_terms.empty() && !world_.pair_terms_run)
    s.fail("pair_terms", "no stage of the pipeline runs pair terms; they act in a \"wcsph\" stage");
}

// Every part a stage needs is built by a stage before it, and no part twice;
// returns the body fields the stages read, each allowed in float (mixed
// precision) where every stage that reads it allows that.
std::vector<FieldInfo> Simulation::check_stage_parts() const {
  const auto& entries = scene_.values.objects("pipeline");
  std::vector<StageParts> parts;
  for (const auto& stage : stages_) parts.push_back(stage->parts(world_));
  auto builder = [&](const std::string& part, std::size_t from, std::size_t to) {
    for (std::size_t j = from; j < to; ++j)
      if (std::ranges::find(parts[j].provides, part) != parts[j].provides.end()) return j;
    return to;
  };
  auto where = [&](std::size_t j) { return "stage '" + stage_names_[j] + "' (/pipeline/" + std::to_string(j) + ")"; };
  for (std::size_t i = 0; i < stages_.size(); ++i) {
    for (const std::string& part : parts[i].needs) {
      if (builder(part, 0, i) < i) continue;
      const std::size_t later = builder(part, i + 1, stages_.size());
      if (later < stages_.size())
        entries[i].fail("", "stage '" + stage_names_[i] + "' needs the " + part + " that " + where(later) +
                                " builds; list that stage before it");
      entries[i].fail("", "stage '" + stage_names_[i] + "' needs " + part + ", which no stage of the pipeline builds");
    }
    for (const std::string& part : parts[i].provides)
      if (const std::size_t earlier = builder(part, 0, i); earlier < i)
        entries[i].fail("", "stage '" + stage_names_[i] + "' builds the " + part + " that " + where(earlier) +
                                " already builds; list only one of them");
  }
  std::vector<FieldInfo> fields;
  for (std::size_t i = 0; i < stages_.size(); ++i)
    for (const std::string& name : parts[i].body_fields) {
      const auto known = std::ranges::find(kBodyFields, name, &FieldInfo::name);
      if (known == std::end(kBodyFields))
        entries[i].fail("", "stage '" + stage_names_[i] + "' reads the start state of the body field '" + name +
                                "', which bodies do not give; they give velocity, density, pressure and mass");
      const bool single = std::ranges::find(parts[i].single_body_fields, name) != parts[i].single_body_fields.end();
      auto listed = std::ranges::find(fields, name, &FieldInfo::name);
      if (listed == fields.end()) {
        fields.push_back(*known);
        fields.back().single_when_mixed = single;
      } else {
        listed->single_when_mixed = listed->single_when_mixed && single;
      }
    }
  return fields;
}

void Simulation::build_writers() {
  const ParamValues& s = scene_.values;
  const auto& names = s.model_names("outputs");
  const auto& params = s.objects("outputs");
  for (std::size_t i = 0; i < names.size(); ++i) {
    ScheduledWriter w;
    w.type = names[i];
    w.writer = registry_.create_as<Writer>("writer", names[i], params[i]);
    if (params[i].has("every") && params[i].has("every_steps"))
      params[i].fail("every_steps", "give either \"every\" or \"every_steps\", not both");
    if (params[i].has("every_steps"))
      w.every_steps = static_cast<std::uint64_t>(params[i].integer("every_steps"));
    else
      w.every = params[i].has("every") ? params[i].real("every") : world_.end_time / 50.0;
    w.writer->check(world_);
    writers_.push_back(std::move(w));
  }
}

}  // namespace talus
