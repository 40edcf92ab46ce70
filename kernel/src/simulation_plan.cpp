// `talus plan`: the resolved scene, pipeline, fields, outputs and plugins,
// printed from the built simulation without running it.
#include "simulation.hpp"

#include <algorithm>
#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "talus/number_text.hpp"
#include "plugin_registry.hpp"
#include "talus/stage.hpp"
#include "talus/writer.hpp"
#include "text.hpp"

namespace talus {

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
  for (const auto& warning : world_.warnings.all()) out << "warning: " << warning << "\n";
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

}  // namespace talus
