#include "depth_integrated_sph.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "esri_ascii.hpp"
#include "follow_surface.hpp"
#include "talus/output_name.hpp"
#include "talus/error.hpp"
#include "talus/geometry.hpp"
#include "talus/sph/pair_loop.hpp"
#include "talus/world.hpp"

namespace talus::runout {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
// Below this many particles a step's loops run on one thread: a fork/join
// per loop costs more than the work (and far more on a loaded machine).
constexpr std::size_t parallel_min = 1024;

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

// The value of the raster cell holding plan point p (a raster is piecewise
// constant); `outside` beyond its cells or on a no-data cell.
double cell_value(const Grid& g, const Vec3& p, double outside) {
  const double fx = (p.x - g.x0) / g.cell, fy = (p.y - g.y0) / g.cell;
  if (!(fx >= -0.5 && fy >= -0.5 && fx < g.ncols - 0.5 && fy < g.nrows - 0.5)) return outside;
  const int c = std::clamp(static_cast<int>(std::lround(fx)), 0, g.ncols - 1);
  const int r = std::clamp(static_cast<int>(std::lround(fy)), 0, g.nrows - 1);
  return g.at(c, r) != g.nodata ? g.at(c, r) : outside;
}

// The plan area of one particle of fluid body `bi`: its lattice's cell
// (dp^2, or a box's adjusted spacings).
double plan_area(const World& world, int bi) {
  const Body& body = world.bodies[bi];
  const double dp = body.dp > 0 ? body.dp : world.dp;
  if (!body.params.has("shape")) return dp * dp;  // particles placed by the caller
  return lattice_volume(body.params.alternative("shape"), body.params.alternative_values("shape"), dp, 2);
}

}  // namespace

ParamSet DepthIntegratedSph::describe() {
  ParamSet p{"depth_integrated_sph", "depth-integrated SPH run-out over terrain (plan view, 2D domain)"};
  declare_terrain(p);
  p.real("release_thickness").unit("m").greater_than(0.0).optional()
      .doc("slope-normal thickness of every fluid body's particles at the start (volume = thickness dp^2 / cos)");
  p.path("thickness_raster").optional()
      .doc("ESRI ASCII raster of the slope-normal release thickness (cell under each particle); <= 0, no-data or outside: dropped");
  p.choice("thickness_measured", {"normal", "vertical"}).default_value("normal")
      .doc("what release_thickness and thickness_raster give: the slope-normal thickness, or the vertical one (a "
           "column over the cell, as the strength-reduction hand-off writes it)");
  p.path("basal_shear_raster").optional()
      .doc("ESRI ASCII raster of the basal shear stress (Pa) each particle resists with while it has not moved yet "
           "(the limit-state contact shear from strength reduction, seed eq. 30): it sets which part of the mass "
           "starts first; once a particle moves only its rheology's basal law acts");
  p.real("cfl").greater_than(0.0).max(1.0).default_value(0.2)
      .doc("Courant number of dt = cfl l / (sqrt(g h) + |v|)");
  p.boolean("variable_smoothing").default_value(true)
      .doc("smoothing length follows the depth (see smoothing_law), within the ratio bounds");
  p.choice("smoothing_law", {"area", "depth"}).default_value("area")
      .doc("area: l = (h_over_dp) sqrt(V / sigma), spacing of a flow spreading in plan; depth: l = l0 sigma0 / sigma, "
           "spacing of a flow spreading along one direction (channels, 1D dam breaks)");
  p.real("min_smoothing_ratio").greater_than(0.0).default_value(0.5)
      .doc("lower bound of the smoothing length, as a multiple of the scene's h");
  p.real("max_smoothing_ratio").greater_than(0.0).default_value(3.0)
      .doc("upper bound of the smoothing length (thin fronts), as a multiple of the scene's h");
  p.real("artificial_viscosity").min(0.0).default_value(0.1)
      .doc("Monaghan alpha of an artificial viscosity between approaching particles (wave speed sqrt(g h)): damps the "
           "particle noise that otherwise grows over long runs at fine resolution; a flow moving as a whole or "
           "spreading does not feel it; 0 for a strictly conservative run");
  p.real("depth_threshold").unit("m").min(0.0).default_value(0.01)
      .doc("thickness above which a raster cell counts as reached (arrival time, peak velocity)");
  p.string("rasters").optional()
      .doc("prefix of the rasters (PREFIX_peak_thickness.asc, ...) written into the output folder at the end of the run");
  p.real("raster_cell").unit("m").greater_than(0.0).optional()
      .doc("raster cell size over the domain for analytic terrain (default: the particle spacing); DEMs use their grid");
  p.integer("raster_every").min(1).default_value(std::int64_t{5}).doc("update the peak rasters every N steps");
  p.check([](const ParamValues& v, Diagnostics& d) {
    if (!v.has("release_thickness") && !v.has("thickness_raster"))
      d.error(v, "release_thickness", "the initial mass needs a thickness",
              "give release_thickness (m) or thickness_raster (.asc)");
    if (v.has("release_thickness") && v.has("thickness_raster"))
      d.error(v, "thickness_raster", "give either release_thickness or thickness_raster, not both");
    if (v.real("min_smoothing_ratio") > 1.0 || v.real("max_smoothing_ratio") < 1.0)
      d.error(v, "max_smoothing_ratio", "the smoothing bounds must include 1", "min_smoothing_ratio <= 1 <= max");
  });
  check_output_name(p, "rasters");
  return p;
}

DepthIntegratedSph::DepthIntegratedSph(const ParamValues& v)
    : params_(v),
      cfl_(v.real("cfl")),
      threshold_(v.real("depth_threshold")),
      variable_smoothing_(v.boolean("variable_smoothing")),
      depth_law_(v.string("smoothing_law") == "depth"),
      raster_every_(v.integer("raster_every")),
      viscosity_(v.real("artificial_viscosity")) {
  if (v.has("rasters")) raster_prefix_ = v.string("rasters");
}

void DepthIntegratedSph::setup(World& world) {
  const std::string where = "error: " + params_.file() + ": " + params_.pointer() + ": ";
  if (world.dim != 2)
    throw InputError(where + "depth_integrated_sph works in plan view (x, y) and needs \"domain\": {\"dim\": 2}; "
                             "got dim " + std::to_string(world.dim));
  g_ = norm(world.gravity);
  if (!(g_ > 0.0)) throw InputError(where + "depth_integrated_sph needs gravity; its magnitude acts along -Z");
  if (world.kernel.dim() != 2 || !(world.dp > 0.0))
    throw InputError(where + "depth_integrated_sph needs a 2D SPH kernel (scene \"kernel\") and a fluid body");
  kernel_ = VariableKernel(world.kernel);
  kappa_ = world.h / world.dp;
  dp_ = world.dp;
  l_min_ = params_.real("min_smoothing_ratio") * world.h;
  l_max_ = params_.real("max_smoothing_ratio") * world.h;
  if (!variable_smoothing_) l_min_ = l_max_ = world.h;

  terrain_ = make_terrain(params_);
  const ParamValues& terrain_values = params_.alternative_values("terrain");
  if (const Grid* dem = terrain_->grid()) {
    // A domain on the DEM's own edges may differ from them by the rounding of the file's header (10 digits):
    // that is not reaching beyond.
    const double half = 0.5 * dem->cell;
    const double slack = 1e-9 * (dem->cell + std::max({std::abs(dem->x0), std::abs(dem->x_max()), std::abs(dem->y0),
                                                       std::abs(dem->y_max())}));
    if (world.lo.x < dem->x0 - half - slack || world.hi.x > dem->x_max() + half + slack ||
        world.lo.y < dem->y0 - half - slack || world.hi.y > dem->y_max() + half + slack)
      throw InputError(where + "the domain [" + std::to_string(world.lo.x) + ", " + std::to_string(world.hi.x) +
                       "] x [" + std::to_string(world.lo.y) + ", " + std::to_string(world.hi.y) +
                       "] reaches beyond the DEM " + terrain_->summary() + "; shrink the domain");
  }
  notes_ = {"terrain: " + terrain_->summary(), "gravity " + format("%.4g", g_) + " m/s^2 along -Z"};
  // Level 0 holds l <= sqrt(2) h: particles at the scene's h (the start, a
  // uniform layer) sit mid-level, not astride a level boundary.
  grid_.configure(2, world.lo, world.hi, kernel_.support * world.h * std::sqrt(2.0), world.periodic);

  ParticleStore& s = world.fluid;
  s.require({"velocity", FieldType::vector, "m/s", true, true});
  s.require({"volume", FieldType::scalar, "m^3", true, true});
  s.require({"mass", FieldType::scalar, "kg", true, true});
  s.require({"depth", FieldType::scalar, "m", true, true});
  s.require({"smoothing_length", FieldType::scalar, "m", false, true});
  s.require({"speed", FieldType::scalar, "m/s", true, false});
  s.require({"elevation", FieldType::scalar, "m", true, false});
  s.require({"basal_shear", FieldType::scalar, "Pa", true, false});

  // Release: thickness per particle, dropping those with none.
  Grid thickness, resistance;
  const bool from_raster = params_.has("thickness_raster");
  const auto read_raster = [](const std::string& f) { return read_esri_ascii(f, true); };
  if (from_raster) thickness = params_.read_file("thickness_raster", read_raster);
  const bool vertical = params_.string("thickness_measured") == "vertical";
  const bool resists = params_.has("basal_shear_raster");
  if (resists) {
    resistance = params_.read_file("basal_shear_raster", read_raster);
    s.require({"initial_basal_shear", FieldType::scalar, "Pa", true, true});
  }
  {
    auto pos = s.position();
    auto body = s.body();
    auto mat = s.material();
    auto vol = s.scalar("volume");
    std::vector<std::uint8_t> drop(s.size(), 0);
    std::size_t dropped = 0;
    std::vector<double> area(world.bodies.size());
    for (std::size_t b = 0; b < area.size(); ++b) area[b] = plan_area(world, static_cast<int>(b));
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (mat[i] < 0 || mat[i] >= static_cast<int>(world.materials.size()))
        throw InputError(where + "fluid particle " + std::to_string(i) + " has no material");
      double t = params_.has("release_thickness") ? params_.real("release_thickness") : 0.0;
      if (from_raster) t = cell_value(thickness, pos[i], 0.0);
      if (!(t > 0.0)) {
        drop[i] = 1;
        ++dropped;
        continue;
      }
      if (!terrain_->defined(pos[i].x, pos[i].y)) {
        const std::string name = body[i] >= 0 && body[i] < static_cast<int>(world.bodies.size())
                                     ? "body '" + world.bodies[body[i]].name + "'" : "a fluid body";
        terrain_values.fail("file", "the release of " + name + " reaches " +
                                        format("(%.6g, %.6g)", pos[i].x, pos[i].y) +
                                        ", where the DEM '" + terrain_values.string("file") +
                                        "' has no surface (a no-data cell among the 4 x 4 cells its "
                                        "bicubic surface and curvature need); fill the hole (e.g. gdal_fillnodata) or "
                                        "move the release");
      }
      const Vec3 gz = terrain_->gradient(pos[i].x, pos[i].y);
      // A vertical column over the particle's plan area (dp^2, or a box's adjusted spacings).
      const bool has_body = body[i] >= 0 && body[i] < static_cast<int>(area.size());
      vol[i] = (vertical ? t : t * std::sqrt(1.0 + gz.x * gz.x + gz.y * gz.y)) *
               (has_body ? area[body[i]] : world.dp * world.dp);
      if (resists) s.scalar("initial_basal_shear")[i] = std::max(cell_value(resistance, pos[i], 0.0), 0.0);
    }
    if (dropped) {
      s.remove_if(drop);
      notes_.push_back(std::to_string(dropped) + " particles outside the thickness raster dropped");
    }
  }
  if (s.size() == 0) throw InputError(where + "no fluid particles to release (no fluid body, or zero thickness)");
  world.refresh_material_index();

  // Materials: each needs a basal shear stress model (none: frictionless).
  materials_.clear();
  for (std::size_t m = 0; m < world.materials.size(); ++m) {
    if (world.material_particles(static_cast<int>(m)).empty()) continue;
    const Material& mat = world.materials[m];
    if (!(mat.density > 0.0)) throw InputError(where + "material '" + mat.name + "' needs a density > 0");
    if (mat.rheology && !mat.rheology->has_basal_shear())
      throw InputError("error: " + (mat.params.file().empty() ? params_.file() : mat.params.file()) +
                       ": /materials/" + mat.name +
                       "/rheology: this rheology has no basal shear stress for depth-integrated flow; allowed: "
                       "coulomb, voellmy, bingham, newtonian");
    notes_.push_back("material '" + mat.name + "': " + (mat.rheology ? "basal shear from its rheology" : "frictionless (no rheology)"));
    materials_.push_back(static_cast<int>(m));
  }

  {
    auto vol = s.scalar("volume");
    auto mass = s.scalar("mass");
    auto vel = s.vector("velocity");
    auto mat = s.material();
    for (std::size_t i = 0; i < s.size(); ++i) {
      mass[i] = world.materials[mat[i]].density * vol[i];
      vel[i].z = 0.0;
    }
    auto l = s.scalar("smoothing_length");
    std::fill(l.begin(), l.end(), world.h);
  }

  compute_depth(world, 3);

  // Crown: the highest released point; run-out is measured from it in plan.
  auto pos = s.position();
  std::size_t top = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (z_[i] > z_[top]) top = i;
  crown_ = pos[top];

  Grid layout;
  if (const Grid* dem = terrain_->grid()) {
    layout = *dem;
  } else {
    const double cell = params_.has("raster_cell") ? params_.real("raster_cell") : world.dp;
    layout.cell = cell;
    layout.x0 = world.lo.x + 0.5 * cell;
    layout.y0 = world.lo.y + 0.5 * cell;
    layout.resize(std::max(2, static_cast<int>(std::ceil((world.hi.x - world.lo.x) / cell))),
                  std::max(2, static_cast<int>(std::ceil((world.hi.y - world.lo.y) / cell))), 0.0);
  }
  rasters_.configure(layout, *terrain_, threshold_);
  record(world);
}

// Bins the particles by search radius (kernel support x smoothing length).
void DepthIntegratedSph::bin_particles(std::span<const Vec3> pos, std::span<const double> smoothing) {
  reach_.resize(pos.size());
  const double sup = kernel_.support;
  for (std::size_t i = 0; i < pos.size(); ++i) reach_[i] = sup * smoothing[i];
  grid_.build(pos, reach_);
}

void DepthIntegratedSph::update_smoothing(std::span<const double> volume, std::span<double> smoothing) const {
  if (!variable_smoothing_) return;
  const double k = kappa_, lo = l_min_, hi = l_max_, k_depth = kappa_ / dp_;
  if (depth_law_) {
#pragma omp parallel for schedule(static) if (volume.size() > parallel_min)
    for (std::size_t i = 0; i < volume.size(); ++i) smoothing[i] = std::clamp(k_depth * volume[i] / sigma_[i], lo, hi);
  } else {
#pragma omp parallel for schedule(static) if (volume.size() > parallel_min)
    for (std::size_t i = 0; i < volume.size(); ++i)
      smoothing[i] = std::clamp(k * std::sqrt(volume[i] / sigma_[i]), lo, hi);
  }
}

// Samples the terrain and computes sigma (and the smoothing length) at the
// current positions, `iterations` times, for setup.
void DepthIntegratedSph::compute_depth(World& world, int iterations) {
  ParticleStore& s = world.fluid;
  const std::size_t n = s.size();
  z_.resize(n);
  cos_.resize(n);
  sigma_.resize(n);
  alpha_.resize(n);
  grad_.resize(n);
  hess_.resize(n);
  auto pos = s.position();
  auto vol = s.scalar("volume");
  auto ell = s.scalar("smoothing_length");
  terrain_->sample(pos, z_.data(), grad_.data(), hess_.data());
  for (std::size_t i = 0; i < n; ++i) cos_[i] = 1.0 / std::sqrt(1.0 + norm2(grad_[i]));
  for (int it = 0; it < iterations; ++it) {
    bin_particles(pos, ell);
    sum_depth(world);
    update_smoothing(vol, ell);
  }
  auto elev = s.scalar("elevation");
  std::copy(z_.begin(), z_.end(), elev.begin());
}

// sigma, the slope-normal depth and the grad-h factor at the current
// positions and smoothing lengths (the particles binned for them).
//    With l = l(sigma), the variational ("grad-h") factor
//    alpha_i = 1 - (d sigma_i / d l_i)(d l_i / d sigma_i) enters the pressure
//    force (Rodriguez-Paz & Bonet 2005, Comput. Struct. 83): for the area law
//    alpha_i = -1 / (2 sigma_i) sum_j V_j r_ij dW/dr(r_ij, l_i); 1 where l is
//    at a bound (or fixed). It keeps thin fronts moving at the right speed.
void DepthIntegratedSph::sum_depth(World& world) {
  ParticleStore& s = world.fluid;
  const std::size_t n = s.size();
  auto pos = s.position();
  auto vol = s.scalar("volume");
  auto ell = s.scalar("smoothing_length");
  auto depth = s.scalar("depth");
  const VariableKernel kern = kernel_;
  const double sup = kern.support;
  const double lo_l = l_min_, hi_l = l_max_;
  const bool area_law = variable_smoothing_ && !depth_law_, depth_law = variable_smoothing_ && depth_law_;
#pragma omp parallel for schedule(static) if (n > parallel_min)
  for (std::size_t i = 0; i < n; ++i) {
    const double li = ell[i];
    double sum = 0.0, moment = 0.0;
    grid_.for_each_neighbour(pos[i], sup * li, [&](Index j, const Vec3&, double r2) {
      const double r = std::sqrt(r2);
      sum += vol[j] * kern.w(r, li);
      moment += vol[j] * r2 * kern.dw_over_r(r, li);
    });
    sigma_[i] = sum;
    depth[i] = cos_[i] * sum;
    double alpha = 1.0;
    if (li > lo_l * (1.0 + 1e-12) && li < hi_l * (1.0 - 1e-12)) {
      if (area_law) alpha = -0.5 * moment / sum;
      else if (depth_law) alpha = -1.0 - moment / sum;
    }
    alpha_[i] = 1.0 / std::max(alpha, alpha_floor_);
  }
}

double DepthIntegratedSph::stable_time_step(World& world) {
  const ParticleStore& s = world.fluid;
  if (s.size() == 0) return inf;
  auto depth = s.scalar("depth");
  auto ell = s.scalar("smoothing_length");
  auto speed = s.scalar("speed");
  double dt = inf;
  const double g = g_;
#pragma omp parallel for reduction(min : dt) schedule(static) if (s.size() > parallel_min)
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double c = std::sqrt(g * std::max(depth[i], 0.0)) + speed[i];
    if (c > 0.0) dt = std::min(dt, ell[i] / c);
  }
  dt *= cfl_;
  // Driving acceleration bound (a particle starting from rest on a slope).
  const double lmin = *std::min_element(ell.begin(), ell.end());
  const double a = std::max(max_accel_, g);
  dt = std::min(dt, 0.5 * std::sqrt(lmin / a));
  return dt;
}

void DepthIntegratedSph::advance(World& world, double dt) {
  ParticleStore& s = world.fluid;
  const std::size_t n = s.size();
  if (n == 0) return;
  if (speed_.size() != n) {
    z_.resize(n); cos_.resize(n); sigma_.resize(n); speed_.resize(n); density_.resize(n); gn_.resize(n);
    tau_.resize(n); hold_.resize(n); whole_speed_.resize(n); grad_.resize(n); next_grad_.resize(n); trial_.resize(n);
    hess_.resize(n); accel_.resize(n); alpha_.resize(n);
  }
  auto pos = s.position();
  auto vel = s.vector("velocity");
  auto vol = s.scalar("volume");
  auto ell = s.scalar("smoothing_length");
  auto depth = s.scalar("depth");
  auto mat = s.material();
  const double g = g_;

  // 1. Terrain under each particle.
  terrain_->sample(pos, z_.data(), grad_.data(), hess_.data());
#pragma omp parallel for schedule(static) if (n > parallel_min)
  for (std::size_t i = 0; i < n; ++i) cos_[i] = 1.0 / std::sqrt(1.0 + norm2(grad_[i]));

  // 2. Depth: sigma_i = sum_j V_j W(r_ij, l_i) (gather). The smoothing
  //    length then follows this depth before the pressure force uses it:
  //    one a step behind the positions (updated after the drift) fed a slowly
  //    growing transverse instability at fine resolution (a lens swinging in a
  //    parabolic canal lost its symmetry after one swing at a/89).
  bin_particles(pos, ell);
  sum_depth(world);
  if (variable_smoothing_) {
    update_smoothing(vol, ell);
    bin_particles(pos, ell);
  }
  const VariableKernel kern = kernel_;
  const double sup = kern.support;

  // 3. Pressure gradient (symmetric in i, j: momentum-conserving on a plane)
  //    mapped to the surface, plus gravity along the slope.
  double amax = 0.0;
  const double viscosity = viscosity_;
  if (viscosity > 0.0) {
    wave_.resize(n);
#pragma omp parallel for schedule(static) if (n > parallel_min)
    for (std::size_t i = 0; i < n; ++i) wave_[i] = std::sqrt(g * std::max(depth[i], 0.0));
  }
#pragma omp parallel for schedule(static) reduction(max : amax) if (n > parallel_min)
  for (std::size_t i = 0; i < n; ++i) {
    const double li = ell[i], ci2 = cos_[i] * cos_[i];
    Vec3 a{};
    grid_.for_each_candidate_pair(pos[i], sup * li, [&](Index j, const Vec3& dx, double r2) {
      const double r = std::sqrt(r2);
      const double lj = ell[j];
      if (r >= sup * std::max(li, lj)) return;
      const double wi = kern.dw_over_r(r, li), wj = kern.dw_over_r(r, lj);
      double f = 0.5 * g * (ci2 + cos_[j] * cos_[j]) * 0.5 * (wi * alpha_[i] + wj * alpha_[j]);
      const double approach = dot(vel[i] - vel[j], dx);
      if (viscosity > 0.0 && approach < 0.0) {
        const double lm = 0.5 * (li + lj);
        const double mu = lm * approach / (r2 + sph::pair_eta2(lm));
        const double c = 0.5 * (wave_[i] + wave_[j]);
        f -= viscosity * c * mu / (0.5 * (sigma_[i] + sigma_[j])) * 0.5 * (wi + wj);
      }
      a -= (vol[j] * f) * dx;
    });
    const Vec3 gz = grad_[i];
    // The earth pressure's own change with the slope: the hydrostatic energy
    // 1/2 g cos^2(theta_i) sigma_i per unit volume depends on x_i through
    // cos^2 = 1 / (1 + |grad Z|^2) too, -1/2 g sigma grad(cos^2) = g sigma cos^4 H grad Z.
    const Hessian& H = hess_[i];
    a += (g * sigma_[i] * ci2 * ci2) * Vec3{H.xx * gz.x + H.xy * gz.y, H.xy * gz.x + H.yy * gz.y, 0.0};
    // (I + gz gz^T)^-1 a = a - gz (gz . a) / (1 + |gz|^2) = a - gz (gz . a) cos^2
    a -= (dot(gz, a) * ci2) * gz;
    const Vec3 gravity = -(g * ci2) * gz;
    a.z = 0.0;
    accel_[i] = a + 0.5 * gravity;  // gravity's other half-kick comes at the end of the step
    amax = std::max(amax, norm(a + gravity));
  }
  max_accel_ = amax;

  // 4. Kick with the pressure force and half of gravity (gravity is split
  //    kick-drift-kick around the drift, second order along curved terrain,
  //    where a whole kick before the drift loses energy at O(dt) over each
  //    swing); speed along the surface; the normal
  //    load per unit mass with its centrifugal part, g_n = cos (g + v.H.v),
  //    never below zero (a flow leaving a convex bend carries no friction).
  std::size_t lifted = 0;
#pragma omp parallel for schedule(static) reduction(+ : lifted) if (n > parallel_min)
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 v = vel[i] + dt * accel_[i];
    v.z = 0.0;
    vel[i] = v;
    const double vz = dot(grad_[i], v);
    speed_[i] = std::sqrt(norm2(v) + vz * vz);
    // The speed the step's whole kick would give (gravity's second half at
    // this point): friction that can absorb it holds the particle.
    const Vec3 whole = v - (0.5 * dt * g * cos_[i] * cos_[i]) * grad_[i];
    const double whole_z = dot(grad_[i], whole);
    whole_speed_[i] = std::sqrt(norm2(whole) + whole_z * whole_z);
    density_[i] = world.materials[mat[i]].density;
    const double load = cos_[i] * (g + along(hess_[i], v));
    lifted += load < 0.0;
    gn_[i] = std::max(load, 0.0);
    tau_[i] = 0.0;
  }
  lifted_steps_ += lifted;
  lifted_now_ = lifted;

  // 5. Basal shear: one batch call per material.
  const BasalInputs in{depth.data(), speed_.data(), density_.data(), gn_.data()};
  for (const int m : materials_) {
    const Rheology* rh = world.materials[m].rheology;
    if (rh) rh->basal_shear(world.material_particles(m), in, tau_.data());
  }
  // A particle that has not moved yet resists with its limit-state shear.
  const bool resists = s.has("initial_basal_shear");
  std::span<double> initial = resists ? s.scalar("initial_basal_shear") : std::span<double>{};

  // 6. Friction acts against the motion and at most stops it within the step
  //    (implicit: a particle whose speed friction can absorb this step stops).
  auto shear = s.scalar("basal_shear");
  auto out_speed = s.scalar("speed");
  const Vec3 lo = world.lo, hi = world.hi;
  const auto periodic = world.periodic;
  auto wrap = [&](Vec3 x) {
    for (int k = 0; k < 2; ++k)
      if (periodic[k]) {
        const double L = hi[k] - lo[k];
        if (x[k] < lo[k]) x[k] += L;
        else if (x[k] >= hi[k]) x[k] -= L;
      }
    return x;
  };
#pragma omp parallel for schedule(static) if (n > parallel_min)
  for (std::size_t i = 0; i < n; ++i) {
    if (resists) tau_[i] = std::max(tau_[i], initial[i]);
    const double decel = depth[i] > 0.0 ? tau_[i] / (density_[i] * depth[i]) * dt : 0.0;
    const double sp = speed_[i];
    double factor = 1.0;
    if (decel > 0.0) factor = sp > decel ? 1.0 - decel / sp : 0.0;
    // Held: friction absorbs the whole kick; the particle rests this step.
    // Stopped: it absorbs the first part; it does not drift, and the end of
    // the step weighs friction against the whole kick (its velocity stays in vel).
    if (decel > 0.0 && whole_speed_[i] <= decel) {
      factor = 0.0;
      vel[i] = Vec3{};
      hold_[i] = inf;
    } else {
      hold_[i] = factor == 0.0 ? decel : 0.0;
      if (factor > 0.0) vel[i] *= factor;
    }
    speed_[i] = sp * factor;
    shear[i] = tau_[i];
    if (resists && factor > 0.0) initial[i] = 0.0;  // it moves: from now on the basal law alone
    trial_[i] = factor > 0.0 ? wrap(pos[i] + dt * vel[i]) : pos[i];
  }

  // 6a. Drift along the surface: the plan step dt v covers dt |u| of surface
  //     only on a plane. Where the slope changes, the step is scaled so that
  //     its length on the surface (with the mean of the gradients at its two
  //     ends) is dt |u|; without this the path length, and so the potential
  //     energy released, is off by O(dt^2) per step, always in one direction
  //     over an oscillation (a slow energy drift). On a plane nothing changes.
  terrain_->sample(trial_, z_.data(), next_grad_.data(), hess_.data());
#pragma omp parallel for schedule(static) if (n > parallel_min)
  for (std::size_t i = 0; i < n; ++i) {
    if (hold_[i] > 0.0) continue;  // stopped
    const Vec3 d = dt * vel[i], mean = 0.5 * (grad_[i] + next_grad_[i]);
    const double rise = dot(mean, d), path = std::sqrt(norm2(d) + rise * rise);
    const double scale = path > 0.0 ? dt * speed_[i] / path : 1.0;
    pos[i] = std::isfinite(scale) ? wrap(pos[i] + scale * d) : trial_[i];
  }

  terrain_->sample(pos, z_.data(), next_grad_.data(), hess_.data());
  auto elev = s.scalar("elevation");
  std::size_t off_terrain = 0;
#pragma omp parallel for schedule(static) reduction(+ : off_terrain) if (n > parallel_min)
  for (std::size_t i = 0; i < n; ++i) {
    elev[i] = z_[i];
    if (!std::isfinite(z_[i])) {
      ++off_terrain;
      continue;
    }
    const Vec3 g1 = next_grad_[i];
    const double c2 = 1.0 / (1.0 + norm2(g1));
    // Gravity's second half-kick, at the new point. A particle friction
    // stopped (it has not moved) stays stopped while friction can absorb the
    // step's whole kick; what friction cannot absorb sets it moving.
    const Vec3 kick = -(0.5 * dt * g * c2) * g1;
    Vec3 v = (hold_[i] > 0.0 ? vel[i] : follow_surface(vel[i], grad_[i], g1, speed_[i])) + kick;
    const double rise = dot(g1, v);
    double sp = std::sqrt(norm2(v) + rise * rise);
    if (hold_[i] == inf) {
      v = Vec3{};
      sp = 0.0;
    } else if (hold_[i] > 0.0) {
      const double factor = sp > hold_[i] ? 1.0 - hold_[i] / sp : 0.0;
      v *= factor;
      sp *= factor;
    }
    vel[i] = v;
    out_speed[i] = sp;
  }

  if (off_terrain) remove_off_terrain(world);

  const bool last = world.end_time > 0.0 && world.time + dt >= world.end_time * (1.0 - 1e-12);
  if (last || (world.step + 1) % static_cast<std::uint64_t>(raster_every_) == 0) {
    // Rasters and run-out at the new time.
    const double t = world.time;
    world.time += dt;
    record(world);
    world.time = t;
  }
}

// Particles over undefined terrain (their elevation is NaN) leave the flow,
// counted with those that leave the domain.
void DepthIntegratedSph::remove_off_terrain(World& world) {
  ParticleStore& s = world.fluid;
  auto elev = s.scalar("elevation");
  std::vector<std::uint8_t> drop(s.size(), 0);
  for (std::size_t i = 0; i < s.size(); ++i) drop[i] = !std::isfinite(elev[i]);
  const std::size_t gone = s.remove_if(drop);
  world.removed += gone;
  off_terrain_ += gone;
  world.refresh_material_index();
}

std::vector<std::string> DepthIntegratedSph::finish(World& world, const std::string& output_directory) {
  std::vector<std::string> lines;
  char line[160];
  std::snprintf(line, sizeof line, "run-out distance %.4g m, deposit volume %.6g m^3", runout_, total_volume(world));
  lines.emplace_back(line);
  if (lifted_steps_)
    lines.push_back(std::to_string(lifted_steps_) + " particle-steps with no basal contact: the centrifugal term over "
                    "convex terrain cancelled gravity's normal part, so those particles followed the surface "
                    "without friction");
  if (off_terrain_)
    lines.push_back(std::to_string(off_terrain_) + " particles flowed onto undefined terrain (DEM no-data) and were "
                    "removed");
  if (!raster_prefix_.empty())
    for (const auto& file : write_rasters(output_directory + "/" + raster_prefix_)) lines.push_back("raster: " + file);
  return lines;
}

void DepthIntegratedSph::record(World& world) {
  ParticleStore& s = world.fluid;
  auto pos = s.position();
  auto depth = s.scalar("depth");
  double runout = runout_;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (depth[i] > threshold_) runout = std::max(runout, norm(pos[i] - crown_));
  }
  runout_ = runout;
  rasters_.record(pos, s.scalar("volume"), s.scalar("smoothing_length"), s.scalar("speed"), kernel_, world.time);
}

std::vector<std::string> DepthIntegratedSph::write_rasters(const std::string& prefix) const {
  return rasters_.write(prefix, *terrain_);
}

double DepthIntegratedSph::total_volume(const World& world) const {
  double v = 0.0;
  for (const double x : world.fluid.scalar("volume")) v += x;
  return v;
}

StagePlan DepthIntegratedSph::plan(const World& world) const {
  StagePlan p;
  p.passes = {"terrain sample (elevation, gradient)", "depth: kernel sum of volumes (pair pass)",
              "pressure gradient + gravity on the slope (pair pass)", "basal shear (rheology batch per material)",
              "friction (stops, never reverses) + drift", "smoothing length from depth",
              "rasters every " + std::to_string(raster_every_) + " steps"};
  p.reads = {"position", "velocity", "volume", "smoothing_length", "material"};
  p.writes = {"position", "velocity", "depth", "smoothing_length", "speed", "elevation", "basal_shear"};
  p.notes = notes_;
  if (!raster_prefix_.empty()) p.notes.push_back("rasters: OUT/" + raster_prefix_ + "_*.asc at the end of the run");
  (void)world;
  return p;
}

std::string DepthIntegratedSph::status(const World& world) const {
  const ParticleStore& s = world.fluid;
  auto speed = s.scalar("speed");
  auto depth = s.scalar("depth");
  std::size_t moving = 0;
  double hmax = 0.0, vmax = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (speed[i] > 0.0) ++moving;
    hmax = std::max(hmax, depth[i]);
    vmax = std::max(vmax, speed[i]);
  }
  std::string line = format("run-out %.4g m, deposit volume %.6g m^3, moving %.3g%%, h max %.3g m", runout_,
                            total_volume(world), s.size() ? 100.0 * moving / s.size() : 0.0, hmax) +
                     format(", v max %.3g m/s", vmax);
  if (lifted_steps_)
    line += ", " + std::to_string(lifted_now_) + " now with no basal contact over convex terrain (" +
            std::to_string(lifted_steps_) + " particle-steps so far)";
  return line;
}

}  // namespace talus::runout
