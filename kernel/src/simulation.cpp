#include "simulation.hpp"

#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <fstream>
#include <ostream>

#include <nlohmann/json.hpp>
#include <sstream>

#include "checkpoint.hpp"
#include "plugin_registry.hpp"
#include "progress.hpp"
#include "talus/blocks.hpp"
#include "talus/boundary.hpp"
#include "talus/build_info.hpp"
#include "talus/cell_list.hpp"
#include "talus/eos.hpp"
#include "talus/error.hpp"
#include "talus/geometry.hpp"
#include "talus/hydrostatic.hpp"
#include "talus/rheology.hpp"
#include "talus/smoothing_kernel.hpp"
#include "talus/stage.hpp"
#include "talus/writer.hpp"
#include "text.hpp"

namespace fs = std::filesystem;

namespace talus {

namespace {

std::atomic<int> stop_signal{0};
extern "C" void on_stop_signal(int sig) { stop_signal.store(sig); }

std::string fixed(double v, int precision = 4) {
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

std::string vec_text(const Vec3& v, int dim) {
  return "(" + fixed(v.x) + ", " + fixed(v.y) + (dim == 3 ? ", " + fixed(v.z) : "") + ")";
}

// Outputs and checkpoints fall due on multiples of their interval. The
// tolerance absorbs rounding in the sum of the steps, but is never a share of
// the interval that would make every step due (an end of 1e308, a 1 ms interval).
double schedule_eps(double end_time, double every) { return std::min(1e-9 * end_time, 1e-3 * every); }

// The first multiple of `every` after `now` (beyond `next`), in one jump.
double next_due(double next, double every, double now, double eps) {
  if (next > now + eps) return next;
  const double intervals = std::floor((now + eps - next) / every) + 1.0;
  return std::max(next + intervals * every, std::nextafter(now + eps, HUGE_VAL));
}

}  // namespace

Simulation::Simulation(PluginRegistry& registry, Scene scene) : registry_(registry), scene_(std::move(scene)) {
  const ParamValues& s = scene_.values;
  const ParamValues& domain = s.object("domain");
  world_.dim = static_cast<int>(domain.integer("dim"));
  world_.lo = domain.vector("min");
  world_.hi = domain.vector("max");
  for (const auto& axis : domain.strings("periodic")) world_.periodic[axis[0] - 'x'] = true;
  world_.gravity = s.vector("gravity");
  world_.end_time = s.object("time").real("end");
  resort_every_ = static_cast<std::uint64_t>(s.object("time").integer("resort_every"));

  build_materials();
  build_kernel();
  check_periodic_axes();
  build_bodies();
  world_.refresh_material_index();
  build_stages();
  world_.refresh_material_index();
  build_writers();
}

Simulation::~Simulation() = default;

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

// The SPH neighbour search (sph::NeighbourGrid) needs a periodic axis of at
// least 2.5 kernel supports; checked once here, with the scene's pointer,
// rather than deep in a stage's setup with neither. A writer that needs more
// says so in its own check.
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
  auto pressure = fluid.scalar("pressure");
  auto rho = fluid.scalar("density");
  for (std::size_t i = 0; i < fluid.size(); ++i) {
    if (!hydrostatic[body[i]]) continue;
    pressure[i] = p[i];
    rho[i] = world.materials[material[i]].eos->density_at(p[i]);
  }
}

}  // namespace

void Simulation::build_bodies() {
  const auto& bodies = scene_.values.objects("bodies");
  ParticleStore& fluid = world_.fluid;
  fluid.require({"velocity", FieldType::vector, "m/s", true, true});
  fluid.require({"density", FieldType::scalar, "kg/m^3", true, true});
  fluid.require({"pressure", FieldType::scalar, "Pa", true, true});
  fluid.require({"mass", FieldType::scalar, "kg", true, true});

  for (std::size_t bi = 0; bi < bodies.size(); ++bi) {
    const ParamValues& v = bodies[bi];
    Body body;
    body.name = v.string("name");
    body.params = v;
    const std::string& kind = v.string("kind");
    body.kind = kind == "fluid" ? BodyKind::fluid : (kind == "wall" ? BodyKind::wall : BodyKind::block);
    if (v.has("material")) body.material = world_.find_material(v.string("material"));
    if (v.has("dp")) body.dp = v.real("dp");
    world_.bodies.push_back(std::move(body));
  }

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
      auto u = fluid.vector("velocity");
      auto rho = fluid.scalar("density");
      auto p = fluid.scalar("pressure");
      auto mass = fluid.scalar("mass");
      auto bid = fluid.body();
      auto mid = fluid.material();
      const Vec3 u0 = v.vector("velocity");
      const double particle_mass = m.density * std::pow(body.dp, world_.dim);
      if (v.boolean("hydrostatic") && !m.eos)
        v.fail("hydrostatic", "needs the material '" + m.name + "' to have an \"eos\"");
      for (std::size_t k = 0; k < points.size(); ++k) {
        const std::size_t i = first + k;
        x[i] = points[k];
        u[i] = u0;
        mass[i] = particle_mass;
        bid[i] = static_cast<std::int32_t>(bi);
        mid[i] = body.material;
        p[i] = 0.0;
        rho[i] = m.density;
      }
    }
    if (v.has("boundary")) {  // walls, and blocks that the fluid sees
      auto boundary = registry_.create_as<Boundary>("boundary", v.model_name("boundary"), v.model_params("boundary"));
      body.boundary = boundary.get();
      models_.push_back(std::move(boundary));
    }
    if (v.has("contact")) {
      auto contact = registry_.create("contact", v.model_name("contact"), v.model_params("contact"));
      body.contact = contact.get();
      models_.push_back(std::move(contact));
    }
  }
  start_hydrostatic(world_, bodies);
  for (std::size_t bi = 0; bi < world_.bodies.size(); ++bi)
    if (world_.bodies[bi].boundary) {
      const int index = static_cast<int>(bi);
      world_.bodies[bi].boundary->setup(world_, std::span<const int>(&index, 1));
    }
}

void Simulation::build_stages() {
  const ParamValues& s = scene_.values;
  const auto& names = s.model_names("pipeline");
  const auto& params = s.objects("pipeline");
  for (std::size_t i = 0; i < names.size(); ++i) {
    stages_.push_back(registry_.create_as<Stage>("stage", names[i], params[i]));
    stage_names_.push_back(names[i]);
  }
  for (auto& stage : stages_) stage->setup(world_);
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

void Simulation::print_plan(std::ostream& out) const {
  const ParamValues& s = scene_.values;
  out << "scene " << scene_.path << (s.has("description") ? ": " + s.string("description") : "") << "\n";
  out << "  domain   " << world_.dim << "D  " << vec_text(world_.lo, world_.dim) << " .. "
      << vec_text(world_.hi, world_.dim);
  std::vector<std::string> periodic;
  for (int a = 0; a < 3; ++a)
    if (world_.periodic[a]) periodic.push_back(std::string(1, static_cast<char>('x' + a)));
  out << (periodic.empty() ? "" : "  periodic " + text::join(periodic)) << "\n";
  out << "  gravity  " << vec_text(world_.gravity, world_.dim) << " m/s^2\n";
  if (!kernel_name_.empty())
    out << "  kernel   " << kernel_name_ << "  h = " << fixed(world_.h) << " m  support = "
        << fixed(world_.kernel.support_radius()) << " m  dp = " << fixed(world_.dp) << " m\n";
  for (const auto& m : world_.materials) {
    out << "  material " << m.name << "  rho0 = " << fixed(m.density) << " kg/m^3";
    if (m.params.has("eos")) out << "  eos " << m.params.model_name("eos");
    if (m.params.has("rheology")) out << "  rheology " << m.params.model_name("rheology");
    out << "  (" << world_.material_particles(world_.find_material(m.name)).size() << " particles)\n";
  }
  const auto fluid_body = world_.fluid.body();
  const auto wall_body = world_.boundary.size() ? world_.boundary.body() : std::span<const std::int32_t>{};
  for (std::size_t bi = 0; bi < world_.bodies.size(); ++bi) {
    const Body& b = world_.bodies[bi];
    out << "  body     " << b.name << "  " << to_string(b.kind) << "  shape " << b.params.alternative("shape");
    if (b.kind == BodyKind::fluid)
      out << "  " << std::count(fluid_body.begin(), fluid_body.end(), static_cast<std::int32_t>(bi)) << " particles";
    if (b.params.has("boundary"))
      out << "  boundary " << b.params.model_name("boundary") << "  "
          << std::count(wall_body.begin(), wall_body.end(), static_cast<std::int32_t>(bi)) << " boundary particles";
    if (b.kind == BodyKind::block && b.params.has("contact")) out << "  contact " << b.params.model_name("contact");
    if (b.params.has("motion")) out << "  motion " << b.params.alternative("motion");
    out << "\n";
  }
  out << "pipeline (each step, in order):\n";
  for (std::size_t i = 0; i < stages_.size(); ++i) {
    const StagePlan plan = stages_[i]->plan(world_);
    out << "  " << i + 1 << ". " << stage_names_[i] << "\n";
    for (std::size_t k = 0; k < plan.passes.size(); ++k) out << "       pass " << k + 1 << ": " << plan.passes[k] << "\n";
    if (!plan.reads.empty()) out << "       reads:  " << text::join(plan.reads) << "\n";
    if (!plan.writes.empty()) out << "       writes: " << text::join(plan.writes) << "\n";
    for (const auto& n : plan.notes) out << "       note: " << n << "\n";
  }
  out << "fields allocated (fluid): ";
  std::vector<std::string> fields;
  for (const auto& f : world_.fluid.fields()) fields.push_back(f.name);
  out << text::join(fields) << "\n";
  if (world_.boundary.size()) {
    fields.clear();
    for (const auto& f : world_.boundary.fields()) fields.push_back(f.name);
    out << "fields allocated (walls): " << text::join(fields) << "\n";
  }
  out << "outputs:\n";
  for (const auto& w : writers_)
    out << "  " << w.type << "  every "
        << (w.every_steps ? std::to_string(w.every_steps) + " steps" : fixed(w.every) + " s") << "\n";
  if (writers_.empty()) out << "  (none)\n";
  out << "end time " << fixed(world_.end_time) << " s\n";
  out << "plugins loaded:\n";
  std::size_t skipped = 0;
  for (const auto& l : registry_.libraries()) {
    if (l.loaded)
      out << "  " << l.plugin_name << " " << l.plugin_version << "  " << l.path << "\n";
    else
      ++skipped;
  }
  out << "  (" << skipped << " other plugin libraries indexed but not loaded: this scene names none of their models)\n";
}

void Simulation::remove_escaped_particles() {
  ParticleStore& fluid = world_.fluid;
  const std::size_t n = fluid.size();
  auto x = fluid.position();
  escaped_.assign(n, 0);
  std::size_t count = 0;
#pragma omp parallel for reduction(+ : count) schedule(static) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < world_.dim; ++a) {
      const double L = world_.hi[a] - world_.lo[a];
      if (world_.periodic[a]) {
        if (x[i][a] < world_.lo[a]) x[i][a] += L;
        if (x[i][a] >= world_.hi[a]) x[i][a] -= L;
      } else if (x[i][a] < world_.lo[a] || x[i][a] > world_.hi[a]) {
        escaped_[i] = 1;
      }
    }
    count += escaped_[i];
  }
  if (count == 0) return;
  world_.removed += fluid.remove_if(escaped_);
  world_.refresh_material_index();
}

void Simulation::resort_particles() {
  if (world_.fluid.size() == 0) return;
  const double cell = world_.h > 0 ? world_.kernel.support_radius() : 2.0 * world_.dp;
  if (!(cell > 0)) return;
  resort_cells_.configure(world_.dim, world_.lo, world_.hi, cell, {});
  resort_cells_.build(world_.fluid.position());
  world_.fluid.reorder(resort_cells_.order());
  world_.refresh_material_index();
}

void Simulation::check_finite() const {
  const ParticleStore& f = world_.fluid;
  const std::size_t n = f.size();
  const auto x = f.position();
  const auto u = f.vector("velocity");
  const auto rho = f.scalar("density");
  const auto p = f.scalar("pressure");
  std::size_t bad = n;
#pragma omp parallel for reduction(min : bad) schedule(static) if (n > 4096)
  for (std::size_t i = 0; i < n; ++i)
    if (!is_finite(x[i]) || !is_finite(u[i]) || !std::isfinite(rho[i]) || !std::isfinite(p[i])) bad = std::min(bad, i);
  if (bad == n) return;
  const char* what = !is_finite(x[bad]) ? "position" : !is_finite(u[bad]) ? "velocity" : !std::isfinite(rho[bad]) ? "density" : "pressure";
  const int body = f.body()[bad];
  std::ostringstream msg;
  msg << "error: step " << world_.step << " (t = " << fixed(world_.time, 6) << " s): particle " << f.ids()[bad]
      << " of body '" << world_.bodies[body].name << "' at " << vec_text(x[bad], world_.dim) << " has non-finite " << what
      << "\n       last good output: " << last_output() << "; stopping.";
  throw RunError(msg.str());
}

std::vector<std::string> Simulation::output_files() const {
  std::vector<std::string> files;
  for (const auto& w : writers_)
    for (auto& f : w.writer->files()) files.push_back(f);
  return files;
}

std::string Simulation::last_output() const {
  std::string newest;
  for (const auto& w : writers_) {
    const auto files = w.writer->files();
    if (!files.empty()) newest = files.back();
  }
  if (newest.empty()) return "none written yet";
  return newest + " (t = " + fixed(last_output_time_) + " s)";
}

void Simulation::write_due_outputs(bool force) {
  for (auto& w : writers_) {
    const double eps = w.every_steps ? 0.0 : schedule_eps(world_.end_time, w.every);
    const bool due = w.every_steps ? world_.step >= w.next_step : world_.time >= w.next_time - eps;
    if (!due && !force) continue;
    w.writer->write(world_);
    last_output_time_ = world_.time;
    if (w.every_steps) {
      while (w.next_step <= world_.step) w.next_step += w.every_steps;
    } else {
      w.next_time = next_due(w.next_time, w.every, world_.time, eps);
    }
  }
}

void Simulation::write_checkpoint(const std::string& path) const {
  RunState state;
  state.scene_hash = text_hash(scene_.text);
  for (const auto& s : stages_) state.stage_states.push_back(s->save_state());
  for (const auto& w : writers_) {
    state.writer_next_time.push_back(w.next_time);
    state.writer_next_step.push_back(w.next_step);
  }
  state.last_output_time = last_output_time_;
  save_checkpoint(path, world_, state);
}

void Simulation::read_checkpoint(const std::string& path) {
  RunState state = load_checkpoint(path, world_, text_hash(scene_.text));
  if (state.stage_states.size() != stages_.size())
    throw InputError("error: checkpoint " + path + ": it has the state of " + std::to_string(state.stage_states.size()) +
                     " stages, this scene's pipeline has " + std::to_string(stages_.size()));
  if (state.writer_next_time.size() != writers_.size())
    throw InputError("error: checkpoint " + path + ": it has the schedule of " +
                     std::to_string(state.writer_next_time.size()) + " outputs, this scene has " +
                     std::to_string(writers_.size()));
  for (std::size_t i = 0; i < stages_.size(); ++i) {
    try {
      stages_[i]->load_state(state.stage_states[i]);
    } catch (const InputError& e) {
      // Stages see only their bytes: the file and the stage are named here.
      std::string why = e.what();
      for (const char* prefix : {"error: checkpoint: ", "error: "})
        if (why.rfind(prefix, 0) == 0) {
          why.erase(0, std::strlen(prefix));
          break;
        }
      throw InputError("error: checkpoint " + path + ": stage " + std::to_string(i + 1) + " (" + stage_names_[i] +
                       "): " + why);
    }
  }
  for (std::size_t i = 0; i < writers_.size(); ++i) {
    writers_[i].next_time = state.writer_next_time[i];
    writers_[i].next_step = state.writer_next_step[i];
  }
  last_output_time_ = state.last_output_time;
  world_.refresh_material_index();
}

int Simulation::run(const RunOptions& options) {
  if (options.threads > 0) omp_set_num_threads(options.threads);
  if (!options.restart.empty()) read_checkpoint(options.restart);

  // Output folder: created only now that every input check has passed.
  output_directory_ = options.output_directory.empty() ? "out/" + scene_.name : options.output_directory;
  std::error_code ec;
  fs::create_directories(output_directory_, ec);
  if (ec) throw RunError("error: cannot create output folder " + output_directory_ + ": " + ec.message());
  if (access(output_directory_.c_str(), W_OK) != 0)
    throw RunError("error: output folder " + output_directory_ + " is not writable: " + std::strerror(errno));

  OutputContext context{output_directory_, scene_.name, scene_.text, TALUS_VERSION_STRING, !options.restart.empty()};
  for (auto& w : writers_) w.writer->open(context, world_);

  const ParamValues& time = scene_.values.object("time");
  const double dt_max = time.has("dt_max") ? time.real("dt_max") : std::numeric_limits<double>::infinity();
  const std::uint64_t max_steps =
      time.has("max_steps") ? static_cast<std::uint64_t>(time.integer("max_steps")) : std::numeric_limits<std::uint64_t>::max();

  // Checkpoint schedule.
  double checkpoint_every = 0.0, checkpoint_minutes = 0.0;
  std::size_t checkpoint_keep = 2;
  if (scene_.values.has("checkpoint")) {
    const ParamValues& c = scene_.values.object("checkpoint");
    if (c.has("every")) checkpoint_every = c.real("every");
    if (c.has("every_minutes")) checkpoint_minutes = c.real("every_minutes");
    checkpoint_keep = static_cast<std::size_t>(c.integer("keep"));
  }
  std::vector<std::string> checkpoints;
  auto checkpoint = [&]() {
    std::ostringstream name;
    name << output_directory_ << "/" << scene_.name << "_" << std::setw(8) << std::setfill('0') << world_.step
         << ".checkpoint";
    write_checkpoint(name.str());
    checkpoints.push_back(name.str());
    while (checkpoints.size() > checkpoint_keep) {
      fs::remove(checkpoints.front(), ec);
      checkpoints.erase(checkpoints.begin());
    }
    return name.str();
  };
  // Checkpoints fall on multiples of `every`, so a restarted run keeps the schedule.
  const double time_eps = checkpoint_every > 0 ? schedule_eps(world_.end_time, checkpoint_every) : 0.0;
  double next_checkpoint_time =
      checkpoint_every > 0 ? (std::floor(world_.time / checkpoint_every + 1e-9) + 1.0) * checkpoint_every : 0.0;

  stop_signal.store(0);
  auto old_int = std::signal(SIGINT, on_stop_signal);
  auto old_term = std::signal(SIGTERM, on_stop_signal);
  struct Restore {
    decltype(old_int) i, t;
    ~Restore() {
      std::signal(SIGINT, i);
      std::signal(SIGTERM, t);
    }
  } restore{old_int, old_term};

  Progress progress(options.quiet, options.progress_seconds);
  const std::uint64_t first_step = world_.step;
  std::uint64_t particle_steps = 0;
  double wall_at_last_checkpoint = 0.0;
  if (options.restart.empty()) write_due_outputs(true);
  if (!options.quiet)
    std::printf("talus: running %s: %zu fluid particles, %zu wall particles%s, to t = %s s; output in %s\n",
                scene_.path.c_str(), world_.fluid.size(), world_.boundary.size(),
                world_.blocks ? (", " + std::to_string(world_.blocks->size()) + " blocks").c_str() : "",
                fixed(world_.end_time).c_str(), output_directory_.c_str());

  try {
    while (world_.time < world_.end_time * (1.0 - 1e-12) && world_.step < max_steps) {
      double dt = std::min(dt_max, world_.end_time - world_.time);
      for (auto& stage : stages_) dt = std::min(dt, stage->stable_time_step(world_));
      if (!(dt > 0.0) || !std::isfinite(dt))
        throw RunError("error: step " + std::to_string(world_.step) + " (t = " + fixed(world_.time, 6) +
                       " s): the stages report no usable time step (dt = " + text::number(dt) + ")");
      for (auto& stage : stages_) stage->advance(world_, dt);
      world_.time += dt;
      ++world_.step;
      particle_steps += world_.fluid.size();
      remove_escaped_particles();
      if (world_.step % resort_every_ == 0) resort_particles();
      check_finite();
      write_due_outputs(false);
      if ((checkpoint_every > 0 && world_.time >= next_checkpoint_time - time_eps) ||
          (checkpoint_minutes > 0 && progress.elapsed() - wall_at_last_checkpoint >= 60.0 * checkpoint_minutes)) {
        checkpoint();
        wall_at_last_checkpoint = progress.elapsed();
        if (checkpoint_every > 0)
          next_checkpoint_time = next_due(next_checkpoint_time, checkpoint_every, world_.time, time_eps);
      }
      std::string status;
      if (options.verbose)
        for (std::size_t i = 0; i < stages_.size(); ++i) {
          const std::string st = stages_[i]->status(world_);
          if (!st.empty()) status += (status.empty() ? "" : "  ") + stage_names_[i] + ": " + st;
        }
      progress.update(world_.time, world_.end_time, dt, world_.step, world_.fluid.size(), status);
      if (const int sig = stop_signal.load()) {
        progress.finish();
        write_due_outputs(true);
        const std::string path = checkpoint();
        for (auto& w : writers_) w.writer->close(world_);
        // The resume command repeats the options that shape the run (threads: the same result bit for bit).
        const std::string threads = options.threads > 0 ? " --threads " + std::to_string(options.threads) : "";
        std::printf("talus: stopped by %s at step %llu (t = %s s); checkpoint written.\n"
                    "       resume with: talus run %s --out %s --restart %s%s\n",
                    sig == SIGINT ? "SIGINT" : "SIGTERM", static_cast<unsigned long long>(world_.step),
                    fixed(world_.time, 6).c_str(), scene_.path.c_str(), output_directory_.c_str(), path.c_str(),
                    threads.c_str());
        return 128 + sig;
      }
    }
  } catch (const RunError&) {
    progress.finish();
    for (auto& w : writers_) {
      try {
        w.writer->close(world_);
      } catch (const std::exception&) {
      }
    }
    throw;
  }
  progress.finish();
  if (last_output_time_ < world_.time) write_due_outputs(true);
  for (auto& w : writers_) w.writer->close(world_);
  std::vector<std::string> finish_lines;
  for (auto& stage : stages_)
    for (auto& line : stage->finish(world_, output_directory_)) finish_lines.push_back(line);

  const double wall = progress.elapsed();
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  if (!options.summary_file.empty()) {
    nlohmann::json summary = {{"scene", scene_.path},
                              {"steps", world_.step - first_step},
                              {"time", world_.time},
                              {"wall_seconds", wall},
                              {"fluid_particles", world_.fluid.size()},
                              {"wall_particles", world_.boundary.size()},
                              {"blocks", world_.blocks ? world_.blocks->size() : 0},
                              {"particle_steps", particle_steps},
                              {"peak_memory_mib", usage.ru_maxrss / 1024.0},
                              {"removed", world_.removed},
                              {"threads", omp_get_max_threads()},
                              {"finish", finish_lines}};
    nlohmann::json statuses = nlohmann::json::object();
    for (std::size_t i = 0; i < stages_.size(); ++i) statuses[stage_names_[i]] = stages_[i]->status(world_);
    summary["stages"] = statuses;
    nlohmann::json files = nlohmann::json::object();
    for (const auto& w : writers_) files[w.type] = w.writer->files();
    summary["outputs"] = files;
    const std::string tmp = options.summary_file + ".tmp";
    {
      std::ofstream out(tmp);
      out << summary.dump(2) << "\n";
      if (!out) throw RunError("error: cannot write " + tmp + ": " + std::strerror(errno));
    }
    fs::rename(tmp, options.summary_file);
  }
  if (!options.quiet) {
    const std::uint64_t steps = world_.step - first_step;
    std::printf("talus: done: %llu steps to t = %s s in %s wall (%.3g steps/s, %.3g M particle-steps/s), peak memory %.0f MiB\n",
                static_cast<unsigned long long>(steps), fixed(world_.time, 6).c_str(), clock_text(wall).c_str(),
                wall > 0 ? steps / wall : 0.0, wall > 0 ? particle_steps / wall / 1e6 : 0.0, usage.ru_maxrss / 1024.0);
    if (world_.removed) std::printf("       %llu fluid particles left the domain and were removed\n",
                                    static_cast<unsigned long long>(world_.removed));
    for (std::size_t i = 0; i < stages_.size(); ++i) {
      const std::string st = stages_[i]->status(world_);
      if (!st.empty()) std::printf("       %s: %s\n", stage_names_[i].c_str(), st.c_str());
    }
    for (const auto& line : finish_lines) std::printf("       %s\n", line.c_str());
    for (const auto& w : writers_) {
      const auto files = w.writer->files();
      if (files.empty()) continue;
      std::printf("       %s: %s%s\n", w.type.c_str(), files.back().c_str(),
                  files.size() > 1 ? (" (and " + std::to_string(files.size() - 1) + " more)").c_str() : "");
    }
  }
  return 0;
}

}  // namespace talus
