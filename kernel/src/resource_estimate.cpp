#include "resource_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "plugin_registry.hpp"
#include "scene.hpp"
#include "shape_estimate.hpp"
#include "talus/memory.hpp"
#include "talus/smoothing_kernel.hpp"
#include "text.hpp"

namespace talus {

namespace {

// Peak resident memory per particle of a run: every field of both stores, the
// neighbour grids' copies of the positions and the stages' per-particle
// scratch together. The growth of peak memory with the particle count of the
// scenes in share/scenes, at the largest (SPH coupled with DDA blocks, 3D),
// rounded up: an estimate that errs on the high side.
constexpr double bytes_per_particle = 600.0;

// A neighbour grid keeps two 4-byte offsets per cell (talus/neighbour_grid.hpp),
// with cells of half the search radius; the fluid, the walls, each block seen
// by the fluid and the periodic re-sort each keep one over the domain.
constexpr double bytes_per_cell = 2.0 * 4.0;

}  // namespace

double ResourceEstimate::bytes() const {
  double sum = 0.0;
  for (const auto& p : parts) sum += p.bytes;
  return sum;
}

const ResourceEstimate::Part* ResourceEstimate::largest() const {
  const Part* best = nullptr;
  for (const auto& p : parts)
    if (!best || p.bytes > best->bytes) best = &p;
  return best;
}

ResourceEstimate estimate_resources(const Scene& scene, PluginRegistry& registry) {
  const ParamValues& s = scene.values;
  const ParamValues& domain = s.object("domain");
  const int dim = static_cast<int>(domain.integer("dim"));
  const Vec3 lo = domain.vector("min"), hi = domain.vector("max");
  const auto& bodies = s.objects("bodies");

  // The spacing and smoothing length the host will use (Simulation::build_kernel).
  double dp_fluid = 0.0, dp_any = 0.0;
  for (const auto& b : bodies) {
    if (!b.has("dp")) continue;
    const double dp = b.real("dp");
    dp_any = dp_any > 0 ? std::min(dp_any, dp) : dp;
    if (b.string("kind") == "fluid") dp_fluid = dp_fluid > 0 ? std::min(dp_fluid, dp) : dp;
  }
  const double dp = dp_fluid > 0 ? dp_fluid : dp_any;
  double support = 0.0;  // search radius, m
  if (s.has("kernel") && dp > 0) {
    const ParamValues& kp = s.model_params("kernel");
    const auto kernel = registry.create_as<SmoothingKernel>("kernel", s.model_name("kernel"), kp);
    support = kernel->support() * kp.real("h_over_dp") * dp;
  }

  ResourceEstimate e;
  const double per_particle = bytes_per_particle;
  int grids = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const ParamValues& b = bodies[i];
    const std::string& kind = b.string("kind");
    const std::string name = "'" + b.string("name") + "'";
    const std::string& alt = b.alternative("shape");
    const ParamValues& shape = b.alternative_values("shape");
    ResourceEstimate::Part part;
    if (kind == "fluid" && b.has("dp")) {
      part = {b.pointer("dp"), "fluid " + name, fill_count_estimate(alt, shape, b.real("dp"), dim, lo, hi), 0.0};
      e.fluid_particles += part.count;
    } else if (kind == "wall" && b.has("boundary")) {
      const double wdp = b.has("dp") ? b.real("dp") : dp;
      if (!(wdp > 0)) continue;
      const double layers = b.has("layers") ? static_cast<double>(b.integer("layers"))
                                            : std::max(1.0, std::ceil(support / wdp - 1e-9));
      part = {b.has("dp") ? b.pointer("dp") : b.pointer(), "wall " + name,
              wall_count_estimate(alt, shape, wdp, dim, layers * wdp, lo, hi), 0.0};
      e.wall_particles += part.count;
      grids = std::max(grids, 2);
    } else if (kind == "block" && b.has("boundary")) {
      const ParamValues& bp = b.model_params("boundary");
      const double bdp = bp.has("dp") ? bp.real("dp") : dp;
      if (!(bdp > 0)) continue;
      const double layers = bp.has("layers") ? static_cast<double>(bp.integer("layers"))
                                             : std::max(1.0, std::ceil(support / bdp - 1e-9));
      const double count = bounding_surface(alt, shape, dim) * layers * bdp / std::pow(bdp, dim);
      part = {bp.has("dp") ? b.pointer("boundary") + "/dp" : b.pointer("boundary"), "block " + name, count, 0.0};
      e.wall_particles += part.count;
      ++grids;
    } else {
      continue;
    }
    part.bytes = part.count * per_particle;
    e.parts.push_back(part);
  }

  if (support > 0 && (e.fluid_particles > 0 || e.wall_particles > 0)) {
    double cells = 1.0;
    for (int a = 0; a < dim; ++a) cells *= std::max(1.0, std::floor(2.0 * (hi[a] - lo[a]) / support));
    e.cells = cells;
    grids += 2;  // the fluid's and the re-sort's
    e.parts.push_back({domain.pointer(), "neighbour-search cells over the domain", cells, cells * grids * bytes_per_cell});
  }

  // Steps: a fixed stage step gives them; dt_max bounds them from below.
  const ParamValues& time = s.object("time");
  const double end = time.real("end");
  const auto& stages = s.objects("pipeline");
  for (const auto& st : stages)
    if (st.has("dt")) {
      const double n = std::ceil(end / st.real("dt") - 1e-9);
      if (e.steps < 0 || n > e.steps) e.steps = n, e.steps_exact = true, e.steps_from = st.pointer("dt");
    }
  if (e.steps < 0 && time.has("dt_max"))
    e.steps = std::ceil(end / time.real("dt_max") - 1e-9), e.steps_from = time.pointer("dt_max");
  return e;
}

void print_estimate(std::ostream& out, const ResourceEstimate& e) {
  out << "estimate (before allocating):\n";
  for (const auto& p : e.parts)
    out << "  " << p.what << ": " << text::number(std::round(p.count)) << (p.what.find("cells") != std::string::npos ? "" : " particles")
        << ", " << memory_text(p.bytes) << "  (" << p.pointer << ")\n";
  out << "  memory: about " << memory_text(e.bytes()) << " of " << memory_text(static_cast<double>(available_memory()))
      << " available\n";
  if (e.steps >= 0)
    out << "  steps: " << (e.steps_exact ? "" : "at least ") << text::number(e.steps) << "  (" << e.steps_from << ")\n";
  else
    out << "  steps: set by the stages' stable time step during the run\n";
}

void check_resources(const Scene& scene, const ResourceEstimate& e) {
  const ResourceEstimate::Part* big = e.largest();
  if (!big) return;
  const std::string count =
      std::isfinite(big->count) ? text::number(std::round(big->count)) : std::string("more than can be counted:");
  require_memory(e.bytes(), scene.path + ": " + big->pointer,
                 "the scene (" + big->what + ": " + count +
                     (big->what.find("cells") != std::string::npos ? "" : " particles") + ", the largest part)");
}

}  // namespace talus
