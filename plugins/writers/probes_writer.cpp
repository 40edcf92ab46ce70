#include "probes_writer.hpp"

#include <algorithm>
#include <numeric>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "field_select.hpp"
#include "talus/output_name.hpp"
#include "talus/blocks.hpp"
#include "talus/world.hpp"
#include "talus/series_file.hpp"
#include "vtu_format.hpp"  // format_real

namespace talus::writers {

namespace {
// The validator gives an absent optional list as an empty one.
bool given_strings(const ParamValues& p, const char* name) { return p.has(name) && !p.strings(name).empty(); }
bool given_points(const ParamValues& p, const char* name) { return p.has(name) && !p.vectors(name).empty(); }

const char* const kIntegralNames[] = {"mass",      "kinetic_energy", "potential_energy",
                                      "particles", "removed",        "max_speed"};
const char* const kIntegralUnits[] = {"kg", "J", "J", "", "", "m/s"};
const char* const kAxis[] = {"x", "y", "z"};

std::string join(const std::vector<std::string>& items, const char* sep) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) out += sep;
    out += items[i];
  }
  return out;
}

std::string point_text(const Vec3& p, int dim) {
  std::string out = "(";
  for (int a = 0; a < dim; ++a) out += (a ? ", " : "") + format_real(p[a]);
  return out + ")";
}
}  // namespace

ParamSet ProbesWriter::describe() {
  ParamSet p{"probes", "CSV time series: SPH-interpolated fields at points, wave gauges, integral quantities"};
  p.string("file").optional().doc("file name in the output folder; default SCENE_probes.csv");
  p.vector_list("points").optional().unit("m").doc("points where fields are interpolated (Shepard kernel average)");
  p.string_list("point_names").optional().doc("column prefixes of the points, one per point; default P1, P2, ...");
  p.string_list("fields").optional().doc(
      "fields at the points: a scalar, a vector (all components), NAME_x/_y/_z or NAME_mag; default pressure, "
      "velocity");
  p.vector_list("gauges").optional().unit("m").doc(
      "wave gauges: a point on each vertical line (its vertical coordinate is ignored); column NAME_elevation, "
      "the free surface's coordinate along the vertical, found scanning down from the side gravity points away "
      "from, or as gauge_reading says (NaN, with a warning, where the line is dry)");
  p.choice("vertical", {"x", "y", "z"})
      .optional()
      .doc("the axis the gauges measure along; default the axis gravity points along (then required when gravity "
           "is zero or along no axis)");
  p.string_list("gauge_names").optional().doc("column prefixes of the gauges, one per gauge; default G1, G2, ...");
  p.vector_list("bed_gauges").optional().unit("m").doc(
      "bed gauges: like gauges, but they find the surface of the particles of one material (a sediment bank's "
      "profile), column NAME_bed; given along a line, in order, they give the bed's eroded and deposited "
      "cross-section between the first and the last row (results bed_eroded_area, bed_deposited_area)");
  p.string_list("bed_gauge_names").optional().doc("column prefixes of the bed gauges; default B1, B2, ...");
  p.string("bed_material").optional().doc("the material whose surface the bed gauges find");
  p.vector_list("runup_line").optional().unit("m").doc(
      "run-up: two points, the line up a slope (from below the still water to above the highest run-up), half a "
      "particle spacing above the slope's surface; column runup_elevation, the vertical coordinate of its highest "
      "wet point (NaN when dry), scanning down from its upper end");
  p.string("runup_material").optional().doc(
      "run-up: count only this material's particles as wet (the water, over a bank of another material)");
  p.real("gauge_step")
      .unit("m")
      .greater_than(0.0)
      .optional()
      .doc("sampling step along a gauge line; default a quarter of the particle spacing");
  p.choice("gauge_reading", {"surface", "wire"})
      .default_value("surface")
      .doc("what the gauges' NAME_elevation is: \"surface\", the highest free surface on the line; \"wire\", what "
           "a wire wave gauge (capacitance or resistance) reads, the line's lowest wet point plus the length of the "
           "line in water above it, so that splash flying over the water adds only its own thickness (both agree "
           "over water wet from its foot up)");
  p.real("gauge_threshold")
      .greater_than(0.0)
      .less_than(1.0)
      .default_value(0.5)
      .doc("kernel fill fraction sum_j V_j W that marks the free surface (0.5 for a flat surface)");
  p.string_list("integrals", {"mass", "kinetic_energy", "potential_energy", "particles", "removed", "max_speed"})
      .optional()
      .doc("integral quantities of the fluid; default mass, kinetic_energy, particles");
  p.string_list("wall_forces")
      .optional()
      .doc(
          "wall bodies whose pressure force from the fluid is written (NAME_fx, NAME_fy[, NAME_fz]): the solver's "
          "pressure term -sum_a sum_j m_a m_j (p_a + p_j)/(rho_a rho_j) grad_a W over the body's wall particles a");
  p.vector_list("wall_sensors")
      .optional()
      .unit("m")
      .doc("wall pressure sensors: points on a wall's surface (half a spacing in front of its first particle layer); "
           "column NAME_pressure = the normal pressure force of the fluid on the wall particles behind the sensor's "
           "patch / the patch's area (a transducer in the wall)");
  p.vector_list("wall_sensor_normals")
      .optional()
      .doc("one per wall sensor: the wall's normal pointing into the fluid (need not be unit)");
  p.string_list("wall_sensor_names").optional().doc("column prefixes of the wall sensors; default W1, W2, ...");
  p.real("wall_sensor_size")
      .unit("m")
      .greater_than(0.0)
      .optional()
      .doc("extent of a wall sensor's patch along the wall (2D: length; 3D: diameter); default the wall's particle "
           "spacing (one row of wall particles)");
  p.object("waves", BreakerAnalysis::describe())
      .optional()
      .doc("at the end of the run, the waves the gauges recorded: heights and period (zero up-crossing), "
           "Iribarren and Froude numbers, breaker type; in the run summary (results/probes) and FILE_results.json "
           "beside the probes file");
  p.boolean("material_masses")
      .default_value(false)
      .doc("the fluid mass of each material, mass_NAME (kg; per metre of depth in 2D): each phase's conservation");
  p.boolean("block_forces")
      .default_value(false)
      .doc("external force on every block (the coupling force of the last step): NAME_fx, NAME_fy[, NAME_fz]");
  check_output_name(p, "file");
  return p;
}

ProbesWriter::ProbesWriter(const ParamValues& params) : params_(params) {
  if (given_points(params, "points")) points_ = params.vectors("points");
  if (given_strings(params, "point_names")) {
    point_names_ = params.strings("point_names");
    if (point_names_.size() != points_.size())
      params.fail("point_names", std::to_string(point_names_.size()) + " names for " + std::to_string(points_.size()) +
                                     " points; give one name per point");
  } else {
    for (std::size_t i = 0; i < points_.size(); ++i) point_names_.push_back("P" + std::to_string(i + 1));
  }
  auto read_gauges = [&](const char* key, const char* names_key, const char* prefix) {
    std::vector<Gauge> gauges;
    if (given_points(params, key)) {
      const auto at = params.vectors(key);
      std::vector<std::string> names;
      if (given_strings(params, names_key)) {
        names = params.strings(names_key);
        if (names.size() != at.size())
          params.fail(names_key, std::to_string(names.size()) + " names for " + std::to_string(at.size()) +
                                     " gauges; give one name per gauge");
      }
      for (std::size_t i = 0; i < at.size(); ++i)
        gauges.push_back({names.empty() ? prefix + std::to_string(i + 1) : names[i], at[i]});
    } else if (given_strings(params, names_key)) {
      params.fail(names_key, "names given but no gauges");
    }
    return gauges;
  };
  gauges_ = read_gauges("gauges", "gauge_names", "G");
  bed_gauges_ = read_gauges("bed_gauges", "bed_gauge_names", "B");
  if (!bed_gauges_.empty() && !params.has("bed_material"))
    params.fail("bed_gauges", "bed gauges need \"bed_material\": the material whose surface they find");
  if (bed_gauges_.size() == 1) bed_change_ = false;
  if (given_points(params, "runup_line")) {
    const auto line = params.vectors("runup_line");
    if (line.size() != 2) params.fail("runup_line", "give two points, the line's ends");
    runup_line_ = {line[0], line[1]};
  } else if (params.has("runup_material")) {
    params.fail("runup_material", "given but no runup_line");
  }
  if (given_points(params, "wall_sensors")) {
    const auto at = params.vectors("wall_sensors");
    const auto normals = given_points(params, "wall_sensor_normals") ? params.vectors("wall_sensor_normals")
                                                                    : std::vector<Vec3>{};
    if (normals.size() != at.size())
      params.fail("wall_sensor_normals", std::to_string(normals.size()) + " normals for " +
                                             std::to_string(at.size()) + " wall sensors; give one normal per sensor");
    std::vector<std::string> names;
    if (given_strings(params, "wall_sensor_names")) {
      names = params.strings("wall_sensor_names");
      if (names.size() != at.size())
        params.fail("wall_sensor_names", std::to_string(names.size()) + " names for " + std::to_string(at.size()) +
                                             " wall sensors; give one name per sensor");
    }
    for (std::size_t i = 0; i < at.size(); ++i) {
      const double length = norm(normals[i]);
      if (!(length > 0.0))
        params.fail("wall_sensor_normals", "the normal of wall sensor " + std::to_string(i + 1) + " is zero");
      const std::string name = names.empty() ? "W" + std::to_string(i + 1) : names[i];
      sensors_.push_back({name, at[i], normals[i] * (1.0 / length), {}, 0, 0.0});
    }
  } else if (given_strings(params, "wall_sensor_names") || given_points(params, "wall_sensor_normals")) {
    params.fail(given_strings(params, "wall_sensor_names") ? "wall_sensor_names" : "wall_sensor_normals",
                "given but no wall_sensors");
  }
  if (params.has("wall_sensor_size")) sensor_size_ = params.real("wall_sensor_size");
  gauge_threshold_ = params.real("gauge_threshold");
  wire_gauges_ = params.string("gauge_reading") == "wire";
  if (params.has("gauge_step")) gauge_step_ = params.real("gauge_step");
  block_forces_ = params.boolean("block_forces");
  material_masses_ = params.boolean("material_masses");
  if (params.has("waves")) {
    std::vector<std::string> gauge_names;
    for (const auto& g : gauges_) gauge_names.push_back(g.name);
    waves_.emplace(params.object("waves"), gauge_names, runup_line_.has_value());
    for (auto& g : gauges_)
      g.air = std::find(waves_->surf_gauges().begin(), waves_->surf_gauges().end(), g.name) != waves_->surf_gauges().end();
  }
  const std::vector<std::string> defaults{"mass", "kinetic_energy", "particles"};
  for (const auto& name : given_strings(params, "integrals") ? params.strings("integrals") : defaults) {
    const auto* it = std::find(std::begin(kIntegralNames), std::end(kIntegralNames), name);
    integrals_.push_back(static_cast<Quantity>(it - std::begin(kIntegralNames)));
  }
}

void ProbesWriter::resolve_columns(const World& world) {
  const ParticleStore& fluid = world.fluid;
  std::vector<std::string> fields;
  if (given_strings(params_, "fields")) {
    fields = params_.strings("fields");
  } else {
    for (const char* f : {"pressure", "velocity"})
      if (fluid.has(f)) fields.emplace_back(f);
  }
  // Per point, the same columns in the same order.
  std::vector<PointColumn> per_point;
  std::vector<std::string> suffix, unit;
  for (const auto& name : fields) {
    if (fluid.has(name)) {
      const auto& info = fluid.info(name);
      if (double_type(info.type) == FieldType::scalar) {  // in double or float
        per_point.push_back({0, name, false, 0});
        suffix.push_back(name);
        unit.push_back(info.unit);
        continue;
      }
      if (double_type(info.type) == FieldType::vector) {
        for (int c = 0; c < world.dim; ++c) {
          per_point.push_back({0, name, true, c});
          suffix.push_back(name + "_" + kAxis[c]);
          unit.push_back(info.unit);
        }
        continue;
      }
      params_.fail("fields", "'" + name + "' is an integer field; only scalar and vector fields can be interpolated");
    }
    const auto us = name.find_last_of('_');
    const std::string base = us == std::string::npos ? name : name.substr(0, us);
    const std::string tail = us == std::string::npos ? "" : name.substr(us + 1);
    int component = -1;
    if (tail == "x") component = 0;
    if (tail == "y") component = 1;
    if (tail == "z" && world.dim == 3) component = 2;
    if (tail == "mag") component = 3;
    if (component < 0 || !fluid.has(base) || double_type(fluid.info(base).type) != FieldType::vector)
      params_.fail("fields", "no particle field or vector component '" + name +
                                 "' in this scene; known fields: " + field_names(fluid));
    per_point.push_back({0, base, true, component});
    suffix.push_back(name);
    unit.push_back(fluid.info(base).unit);
  }

  names_ = {"time", "step"};
  units_ = {"s", ""};
  point_columns_.clear();
  for (std::size_t p = 0; p < points_.size(); ++p)
    for (std::size_t c = 0; c < per_point.size(); ++c) {
      PointColumn col = per_point[c];
      col.point = p;
      point_columns_.push_back(col);
      names_.push_back(point_names_[p] + "_" + suffix[c]);
      units_.push_back(unit[c]);
    }
  for (const auto& g : gauges_) {
    names_.push_back(g.name + "_elevation");
    units_.push_back("m");
  }
  for (const auto& g : gauges_)
    if (g.air) {
      names_.push_back(g.name + "_air_below");
      units_.push_back("m");
    }
  for (const auto& g : gauges_)
    if (g.air) {
      names_.push_back(g.name + "_surface_u");
      units_.push_back("m/s");
    }
  for (const auto& g : bed_gauges_) {
    names_.push_back(g.name + "_bed");
    units_.push_back("m");
  }
  if (runup_line_) {
    names_.push_back("runup_elevation");
    units_.push_back("m");
  }
  if (material_masses_) {
    if (!world.fluid.has("mass"))
      params_.fail("material_masses", "needs the particle field 'mass' (an SPH stage)");
    for (const auto& m : world.materials) {
      names_.push_back("mass_" + m.name);
      units_.push_back("kg");
    }
  }
  for (auto q : integrals_) {
    names_.emplace_back(kIntegralNames[static_cast<int>(q)]);
    units_.emplace_back(kIntegralUnits[static_cast<int>(q)]);
  }
  for (int b : wall_bodies_)
    for (int c = 0; c < world.dim; ++c) {
      names_.push_back(world.bodies[b].name + "_f" + kAxis[c]);
      units_.push_back("N");
    }
  block_count_ = block_forces_ && world.blocks ? world.blocks->size() : 0;
  for (std::size_t b = 0; b < block_count_; ++b)
    for (int c = 0; c < world.dim; ++c) {
      names_.push_back(world.blocks->name[b] + "_f" + kAxis[c]);
      units_.push_back("N");
    }
  for (const auto& w : sensors_) {
    names_.push_back(w.name + "_pressure");
    units_.push_back("Pa");
  }
}

std::string ProbesWriter::comment_lines(const OutputContext& context, const World& world) const {
  std::string out = "# talus probes: scene " + context.scene_name + ", Talus " + context.talus_version + "\n";
  out += "# units: " + join(units_, ",") + "\n";
  if (!points_.empty()) {
    out += "# points:";
    for (std::size_t p = 0; p < points_.size(); ++p)
      out += " " + point_names_[p] + "=" + point_text(points_[p], world.dim);
    out += "\n# interpolation: Shepard kernel average sum_j f_j V_j W / sum_j V_j W, V_j = m_j/rho_j, support " +
           format_real(world.kernel.support_radius()) + " m\n";
  }
  if (!gauges_.empty()) {
    out += std::string(wire_gauges_ ? "# gauges (wire reading: lowest wet point plus wet length, "
                                    : "# gauges (highest free surface, ") +
           "elevation along the " + std::string(kAxis[vertical_]) + " axis, up " +
           (up_ > 0 ? "+" : "-") + kAxis[vertical_] + ", where sum_j V_j W = " + format_real(gauge_threshold_) +
           ", step " + format_real(gauge_step_) + " m):";
    for (const auto& g : gauges_) out += " " + g.name + "=" + point_text(g.at, world.dim);
    out += "\n";
  }
  if (!wall_bodies_.empty())
    out +=
        "# wall forces: pressure force of the fluid on the wall particles of each body, "
        "-sum_a sum_j m_a m_j (p_a + p_j)/(rho_a rho_j) grad_a W (the solver's pressure term), N\n";
  if (!sensors_.empty()) {
    out += "# wall sensors (normal pressure force of the fluid on the wall particles behind a patch of the wall surface "
           "/ the patch area, force as for wall forces):";
    for (const auto& w : sensors_)
      out += " " + w.name + "=" + point_text(w.at, world.dim) + " n=" + point_text(w.normal, world.dim) + " (" +
             std::to_string(w.particle_count) + " wall particles, area " + format_real(w.area) + ")";
    out += "\n";
  }
  if (block_count_ > 0) out += "# block forces: external force of the last step (coupling), N\n";
  return out;
}

std::size_t ProbesWriter::resume_bytes(const std::string& header, std::uint64_t step, std::uint64_t& last_step,
                                       bool& rows) const {
  std::ifstream in(path_, std::ios::binary);
  if (!in) return 0;
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::size_t kept = 0, pos = 0;
  bool header_seen = false;
  while (pos < text.size()) {
    const auto end = text.find('\n', pos);
    if (end == std::string::npos) break;  // an incomplete last line
    const std::string line = text.substr(pos, end - pos);
    if (!line.empty() && line[0] == '#') {
      if (header_seen) break;
    } else if (!header_seen) {
      if (line != header) return 0;  // other columns: start afresh
      header_seen = true;
    } else {
      const auto c1 = line.find(',');
      const auto c2 = line.find(',', c1 + 1);
      if (c1 == std::string::npos) break;
      const std::uint64_t row_step = std::strtoull(line.substr(c1 + 1, c2 - c1 - 1).c_str(), nullptr, 10);
      if (row_step > step) break;
      last_step = row_step;
      rows = true;
    }
    pos = end + 1;
    kept = pos;
  }
  return header_seen ? kept : 0;
}

// A fresh writer from the same parameters does the work of open() short of
// the file, so the check leaves this one as it was.
// The gauges' vertical: the scene's "vertical", else the axis gravity lies
// along; up is against gravity (+axis where gravity has no part along it).
void ProbesWriter::choose_vertical(const World& world) {
  const Vec3 g = world.gravity;
  int along = -1, axes = 0;
  for (int a = 0; a < world.dim; ++a)
    if (g[a] != 0.0) {
      along = a;
      ++axes;
    }
  if (params_.has("vertical")) {
    vertical_ = params_.string("vertical")[0] - 'x';
    if (vertical_ >= world.dim)
      params_.fail("vertical", params_.string("vertical") + " is not an axis of a " + std::to_string(world.dim) +
                                   "D domain");
  } else if (axes == 1) {
    vertical_ = along;
  } else {
    vertical_ = world.dim - 1;
    if (!gauges_.empty())
      params_.fail("gauges", "gravity " + point_text(g, world.dim) +
                                 " points along no axis, so the gauges have no vertical; give \"vertical\": the axis "
                                 "they measure along");
  }
  up_ = g[vertical_] > 0.0 ? -1.0 : 1.0;
}

void ProbesWriter::MaterialSampler::configure(const World& world, const ParamValues& params, const char* key) {
  material = world.find_material(params.string(key));
  if (material < 0 || !world.fluid.has("material"))
    params.fail(key, "'" + params.string(key) + "' is not a fluid material of this scene");
  sampler.configure(world.dim, world.lo, world.hi, world.periodic, world.kernel);
}

void ProbesWriter::MaterialSampler::bind(const ParticleStore& fluid, std::span<const double> all_volumes) {
  const auto of = fluid.integer("material");
  const std::size_t owned = fluid.owned_size();
  volume.resize(owned);
#pragma omp parallel for
  for (std::size_t i = 0; i < owned; ++i) volume[i] = of[i] == material ? all_volumes[i] : 0.0;
  sampler.bind(fluid.position().first(owned), volume);
}

void ProbesWriter::check(const World& world) const { ProbesWriter(params_).prepare(world); }

std::vector<std::string> ProbesWriter::series(const World& world) const {
  ProbesWriter prepared(params_);
  prepared.prepare(world);
  return prepared.names_;
}

// On several MPI ranks every rank samples its own particles and rank 0 alone
// keeps the file.
void ProbesWriter::open(const OutputContext& context, const World& world) {
  check_writable_directory(context.directory);
  prepare(world);
  path_ =
      join_path(context.directory, params_.has("file") ? params_.string("file") : context.scene_name + "_probes.csv");
  results_path_ = (path_.ends_with(".csv") ? path_.substr(0, path_.size() - 4) : path_) + "_results.json";
  const Parallel& ranks = world.parallel();
  writes_file_ = ranks.rank() == 0;
  std::uint64_t last_kept_step = 0;
  bool kept_rows = false;
  if (writes_file_) {
    const std::string header = join(names_, ",");
    const std::size_t keep = context.resume ? resume_bytes(header, world.step, last_kept_step, kept_rows) : 0;
    file_.open(path_, keep);
    if (keep == 0) file_.append(comment_lines(context, world) + header + "\n");
  }
  // After a restart the host may write the checkpoint's state again; every
  // rank must skip that row alike, as each takes part in every row's sums.
  have_last_step_ = ranks.max(kept_rows && last_kept_step == world.step ? 1.0 : 0.0) > 0.0;
  last_step_ = static_cast<std::uint64_t>(ranks.max(static_cast<double>(last_kept_step)));
}

void ProbesWriter::prepare(const World& world) {
  choose_vertical(world);
  if (waves_) {
    std::vector<Vec3> at;
    for (const auto& g : gauges_) at.push_back(g.at);
    waves_->place(params_.object("waves"), at, vertical_);
    if (!world.fluid.has("velocity"))
      params_.fail("waves", "needs the particle field 'velocity' (an SPH stage): the crests' particle speed");
  }
  wall_bodies_.clear();
  if (given_strings(params_, "wall_forces")) {
    for (const auto& name : params_.strings("wall_forces")) {
      const int b = world.find_body(name);
      if (b < 0 || world.bodies[b].kind != BodyKind::wall) {
        std::string walls;
        for (const auto& body : world.bodies)
          if (body.kind == BodyKind::wall) walls += (walls.empty() ? "" : ", ") + body.name;
        params_.fail("wall_forces", "no wall body '" + name + "'; wall bodies: " + (walls.empty() ? "none" : walls));
      }
      wall_bodies_.push_back(b);
    }
  }
  if (!wall_bodies_.empty() || !sensors_.empty()) {
    const char* key = !wall_bodies_.empty() ? "wall_forces" : "wall_sensors";
    for (const char* f : {"mass", "density", "pressure"})
      if (!world.fluid.has(f) || !world.boundary.has(f))
        params_.fail(key, std::string("needs the field '") + f +
                              "' on fluid and wall particles (an SPH stage with wall particles)");
  }
  if (!points_.empty() || !gauges_.empty() || !bed_gauges_.empty() || runup_line_ || !wall_bodies_.empty() ||
      !sensors_.empty()) {
    const char* key = !points_.empty() ? "points"
                      : !gauges_.empty() ? "gauges"
                      : !bed_gauges_.empty() ? "bed_gauges"
                      : runup_line_ ? "runup_line"
                      : !wall_bodies_.empty() ? "wall_forces"
                                              : "wall_sensors";
    if (!(world.kernel.support_radius() > 0.0))
      params_.fail(key, "probes and gauges need an SPH kernel (scene key /kernel)");
    auto inside = [&](const Vec3& p, bool skip_vertical) {
      for (int a = 0; a < world.dim; ++a)
        if (!(skip_vertical && a == vertical_) && (p[a] < world.lo[a] || p[a] > world.hi[a])) return false;
      return true;
    };
    for (std::size_t p = 0; p < points_.size(); ++p)
      if (!inside(points_[p], false))
        params_.fail("points", point_names_[p] + " at " + point_text(points_[p], world.dim) + " is outside the domain");
    for (const auto& g : gauges_)
      if (!inside(g.at, true))
        params_.fail("gauges", g.name + " at " + point_text(g.at, world.dim) + " is outside the domain");
    for (const auto& g : bed_gauges_)
      if (!inside(g.at, true))
        params_.fail("bed_gauges", g.name + " at " + point_text(g.at, world.dim) + " is outside the domain");
    if (runup_line_)
      for (const Vec3& end : *runup_line_)
        if (!inside(end, false))
          params_.fail("runup_line", "the end " + point_text(end, world.dim) + " is outside the domain");
    if (runup_line_ && params_.has("runup_material")) runup_wet_.configure(world, params_, "runup_material");
    if (!bed_gauges_.empty()) bed_.configure(world, params_, "bed_material");
    sampler_.configure(world.dim, world.lo, world.hi, world.periodic, world.kernel);
    force_sampler_.configure(world.dim, world.lo, world.hi, world.periodic, world.kernel);
    if (gauge_step_ <= 0.0) gauge_step_ = world.dp > 0.0 ? 0.25 * world.dp : 0.25 * world.kernel.h();
    top_ = up_ > 0 ? world.hi[vertical_] : world.lo[vertical_];
    bottom_ = up_ > 0 ? world.lo[vertical_] : world.hi[vertical_];
    for (auto* gauges : {&gauges_, &bed_gauges_})
      for (auto& g : *gauges) g.samples = line_samples(g.at, vertical_, top_, bottom_, gauge_step_, 0);
    if (runup_line_) runup_ = slope_samples((*runup_line_)[0], (*runup_line_)[1], vertical_, up_, gauge_step_);
  }
  select_sensor_particles(world);
  resolve_columns(world);
}


// This rank's share: a sum over the particles it owns (its count of removed
// ones), or their peak speed.
double ProbesWriter::integral(Quantity q, const World& world) const {
  const ParticleStore& s = world.fluid;
  const std::size_t n = s.owned_size();
  const bool has_mass = s.has("mass");
  std::vector<double> mass_wide;  // in double, where the store keeps it in float
  std::vector<Vec3> velocity_wide;
  const auto mass = has_mass ? s.scalar_in_double("mass", mass_wide) : std::span<const double>{};
  const auto vel = s.has("velocity") ? s.vector_in_double("velocity", velocity_wide) : std::span<const Vec3>{};
  const auto pos = s.position();
  double sum = 0.0;
  switch (q) {
    case Quantity::particles:
      return static_cast<double>(n);
    case Quantity::removed:
      return static_cast<double>(world.removed);
    case Quantity::mass:
      if (!has_mass) return std::numeric_limits<double>::quiet_NaN();
#pragma omp parallel for reduction(+ : sum)
      for (std::size_t i = 0; i < n; ++i) sum += mass[i];
      return sum;
    case Quantity::kinetic_energy:
      if (!has_mass || vel.empty()) return std::numeric_limits<double>::quiet_NaN();
#pragma omp parallel for reduction(+ : sum)
      for (std::size_t i = 0; i < n; ++i) sum += 0.5 * mass[i] * norm2(vel[i]);
      return sum;
    case Quantity::potential_energy: {
      if (!has_mass) return std::numeric_limits<double>::quiet_NaN();
      const Vec3 g = world.gravity;
#pragma omp parallel for reduction(+ : sum)
      for (std::size_t i = 0; i < n; ++i) sum -= mass[i] * dot(g, pos[i]);
      return sum;
    }
    case Quantity::max_speed: {
      if (vel.empty()) return std::numeric_limits<double>::quiet_NaN();
      double peak = 0.0;
#pragma omp parallel for reduction(max : peak)
      for (std::size_t i = 0; i < n; ++i) peak = std::max(peak, norm2(vel[i]));
      return std::sqrt(peak);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// Over the wall particles this rank owns (their fluid neighbours are owned or
// halo rows, all bound to `fluid`).
Vec3 ProbesWriter::wall_force(int body, const World& world, const SphSampler& fluid) const {
  // The pressure term the solver applies between fluid particles j and the
  // body's wall particles a (sph::PressureForce), from the wall's side:
  //   F = -sum_a m_a sum_j m_j (p_a + p_j)/(rho_a rho_j) grad_a W_aj,
  // minus the force the walls' pressure exerts on the fluid. For a flat wall
  // under a uniform pressure p it tends to p A along the inward normal.
  const ParticleStore& wall = world.boundary;
  const auto owner = wall.body();
  const ForceFields fields(world);
  double fx = 0.0, fy = 0.0, fz = 0.0;
#pragma omp parallel for reduction(+ : fx, fy, fz) schedule(static)
  for (std::size_t a = 0; a < wall.owned_size(); ++a) {
    if (owner[a] != body) continue;
    const Vec3 f = particle_force(a, fields, fluid);
    fx += f.x;
    fy += f.y;
    fz += f.z;
  }
  return {fx, fy, fz};
}

ProbesWriter::ForceFields::ForceFields(const World& world) : xa(world.boundary.position()) {
  ma = world.boundary.scalar_in_double("mass", wall_mass_wide);
  rhoa = world.boundary.scalar_in_double("density", wall_density_wide);
  pa = world.boundary.scalar_in_double("pressure", wall_pressure_wide);
  std::vector<double> rho_wide;
  const auto rho = world.fluid.scalar_in_double("density", rho_wide);
  inv_rho.resize(rho.size());
  for (std::size_t j = 0; j < rho.size(); ++j) inv_rho[j] = 1.0 / rho[j];
  fluid.mass = world.fluid.scalar_in_double("mass", mass_wide).data();
  fluid.pressure = world.fluid.scalar_in_double("pressure", pressure_wide).data();
  fluid.inv_density = inv_rho.data();
}

Vec3 ProbesWriter::particle_force(std::size_t a, const ForceFields& s, const SphSampler& fluid) const {
  struct Sums {
    double p, inv_rho;
    Vec3 acc;
  } sums{s.pa[a], 1.0 / s.rhoa[a], {}};
  const sph::PressureForce pressure{s.fluid};
  const KernelTable& kernel = fluid.kernel();
  fluid.for_each_neighbour(s.xa[a], [&](Index j, const Vec3& dx, double r) {
    sph::Pair q;
    q.j = j;
    q.dx = dx;
    q.r2 = r * r;
    q.r = r;
    q.dw_r = kernel.dw_over_r(r);
    pressure.pair(q, sums);
  });
  return sums.acc * s.ma[a];
}

// The wall particles behind each sensor's patch: at a depth 0 <= -(x_a - at).n
// within the kernel support (deeper ones feel no fluid) and a distance along
// the wall |(x_a - at) - ((x_a - at).n) n| <= size/2. The patch's area is the
// number of those in the first layer (depth < dp) times dp^(dim-1): every
// first-layer particle stands for dp^(dim-1) of the wall surface. On several
// MPI ranks each rank selects among the wall particles it owns, and the
// nearest particle and the first layer's count are taken over all ranks.
void ProbesWriter::select_sensor_particles(const World& world) {
  sensor_wall_size_ = world.boundary.size();
  if (sensors_.empty()) return;
  const Parallel& ranks = world.parallel();
  const ParticleStore& wall = world.boundary;
  const std::size_t owned = wall.owned_size();
  const auto x = wall.position();
  const auto owner = wall.body();
  const double reach = world.kernel.support_radius();
  for (auto& s : sensors_) {
    s.particles.clear();
    s.area = 0.0;
    // The wall's spacing: that of the body of the nearest wall particle behind the surface.
    double best = std::numeric_limits<double>::infinity();
    int body = -1;
    for (std::size_t a = 0; a < owned; ++a) {
      const Vec3 d = x[a] - s.at;
      const double r2 = norm2(d);
      if (dot(d, s.normal) <= 0.0 && r2 < best) {
        best = r2;
        body = owner[a];
      }
    }
    // (Two bodies exactly as near on two ranks: the larger id.)
    const double nearest = ranks.min(best);
    body = static_cast<int>(ranks.max(best == nearest ? static_cast<double>(body) : -1.0));
    const double dp = body >= 0 && world.bodies[body].dp > 0.0 ? world.bodies[body].dp : world.dp;
    const double half = 0.5 * (sensor_size_ > 0.0 ? sensor_size_ : dp) * (1.0 + 1e-9);
    std::uint64_t surface = 0;
    for (std::size_t a = 0; a < owned; ++a) {
      const Vec3 d = x[a] - s.at;
      const double depth = -dot(d, s.normal);
      if (depth < 0.0 || depth > reach + 0.5 * dp) continue;
      if (norm(d + s.normal * depth) > half) continue;
      s.particles.push_back(static_cast<Index>(a));
      if (depth < dp) ++surface;
    }
    surface = ranks.sum(surface);
    if (surface == 0)
      params_.fail("wall_sensors", s.name + " at " + point_text(s.at, world.dim) +
                                       ": no wall particle within one spacing behind it along the normal " +
                                       point_text(s.normal, world.dim) +
                                       "; put the sensor on a wall surface, the normal pointing into the fluid");
    s.area = static_cast<double>(surface) * std::pow(dp, world.dim - 1);
    s.particle_count = ranks.sum(static_cast<std::uint64_t>(s.particles.size()));
  }
}

// This rank's share of the normal force on the sensor's patch (divided by the whole patch's area).
double ProbesWriter::sensor_pressure(const WallSensor& sensor, const World& world, const SphSampler& fluid) const {
  const ForceFields fields(world);
  double push = 0.0;  // the fluid pushes the wall along -n
  for (Index a : sensor.particles) push -= dot(particle_force(a, fields, fluid), sensor.normal);
  return push / sensor.area;
}

// Every value of a row is a sum over particles (a peak speed: a maximum), so
// on several MPI ranks each rank adds up the particles it owns and the ranks'
// shares are added in one message (gauges with air below their surface take a
// second); rank 0 writes the row.
void ProbesWriter::write(const World& world) {
  if (have_last_step_ && world.step == last_step_) return;
  const Parallel& ranks = world.parallel();
  const ParticleStore& fluid = world.fluid;
  const std::size_t owned = fluid.owned_size();
  const bool forces = !wall_bodies_.empty() || !sensors_.empty();
  if (!points_.empty() || !gauges_.empty() || !bed_gauges_.empty() || runup_line_ || forces) {
    const std::size_t n = fluid.size();
    volume_.resize(n);
    if (fluid.has("mass") && fluid.has("density")) {
      const auto m = fluid.scalar_in_double("mass", wide_);
      const auto rho = fluid.scalar_in_double("density", wide_other_);
#pragma omp parallel for
      for (std::size_t i = 0; i < n; ++i) volume_[i] = m[i] / rho[i];
    } else {
      std::fill(volume_.begin(), volume_.end(), std::pow(world.dp, world.dim));
    }
    sampler_.bind(fluid.position().first(owned), std::span<const double>(volume_).first(owned));
  }
  // A wall particle's force reads its fluid neighbours on this rank, owned or halo.
  if (forces && ranks.ranks() > 1) force_sampler_.bind(fluid.position(), volume_);
  const SphSampler& force_fluid = ranks.ranks() > 1 ? force_sampler_ : sampler_;

  shares_.clear();
  auto share = [&](double v) { shares_.push_back(v); };
  auto fill_along = [&](const SphSampler& sampler, const std::vector<Vec3>& samples) {
    const std::size_t at = shares_.size();
    shares_.resize(at + samples.size());
    fill_fractions(sampler, samples, std::span<double>(shares_).subspan(at));
  };
  // Points: the Shepard weight, then a weighted sum per value.
  std::size_t c = 0;
  for (std::size_t p = 0; p < points_.size(); ++p) {
    share(sampler_.gather(points_[p], neighbours_));
    auto weighted = [&](auto&& value) {
      double acc = 0.0;
      for (const auto& nb : neighbours_) acc += nb.weight * value(nb.j);
      share(acc);
    };
    for (; c < point_columns_.size() && point_columns_[c].point == p; ++c) {
      const auto& col = point_columns_[c];
      if (!col.vector) {
        const auto f = fluid.scalar_in_double(col.field, wide_);
        weighted([&](Index j) { return f[j]; });
        continue;
      }
      const auto v = fluid.vector_in_double(col.field, wide_vectors_);
      for (int k = col.component < 3 ? col.component : 0; k < (col.component < 3 ? col.component + 1 : world.dim); ++k)
        weighted([&](Index j) { return v[j][k]; });
    }
  }
  for (const auto& g : gauges_) fill_along(sampler_, g.samples);
  if (!bed_gauges_.empty()) bed_.bind(fluid, volume_);
  for (const auto& g : bed_gauges_) fill_along(bed_.sampler, g.samples);
  if (runup_line_) {
    if (runup_wet_.material >= 0) runup_wet_.bind(fluid, volume_);
    fill_along(runup_wet_.material >= 0 ? runup_wet_.sampler : sampler_, runup_.samples);
  }
  if (material_masses_) {  // summed in particle id order: the re-sort does not change the sum's rounding
    const std::size_t at = shares_.size();
    shares_.resize(at + world.materials.size(), 0.0);
    const auto m = fluid.scalar_in_double("mass", wide_);
    const auto material = fluid.integer("material");
    const auto id = fluid.ids();
    std::vector<Index> by_id(owned);
    std::iota(by_id.begin(), by_id.end(), Index{0});
    std::sort(by_id.begin(), by_id.end(), [&](Index a, Index b) { return id[a] < id[b]; });
    for (Index i : by_id)
      if (material[i] >= 0 && static_cast<std::size_t>(material[i]) < world.materials.size())
        shares_[at + material[i]] += m[i];
  }
  double peak_speed = 0.0;
  for (auto q : integrals_) {
    if (q == Quantity::max_speed) peak_speed = integral(q, world);
    share(q == Quantity::max_speed ? 0.0 : integral(q, world));
  }
  for (int body : wall_bodies_) {
    const Vec3 f = wall_force(body, world, force_fluid);
    for (int k = 0; k < world.dim; ++k) share(f[k]);
  }
  // On several ranks the rows move between frames: the sensors' particles are found again.
  if (!sensors_.empty() && (ranks.ranks() > 1 || world.boundary.size() != sensor_wall_size_))
    select_sensor_particles(world);
  for (const auto& s : sensors_) share(sensor_pressure(s, world, force_fluid));
  ranks.sum(std::span<double>(shares_));
  peak_speed = ranks.max(peak_speed);

  // The row, in the header's order.
  row_.clear();
  row_ += format_real(world.time) + "," + std::to_string(world.step);
  auto put = [&](double v) {
    row_ += ',';
    row_ += format_real(v);
  };
  const double* next = shares_.data();
  c = 0;
  for (std::size_t p = 0; p < points_.size(); ++p) {
    const double weight_sum = *next++;
    auto shepard = [&](double acc) { return weight_sum > 0.0 ? acc / weight_sum : std::numeric_limits<double>::quiet_NaN(); };
    for (; c < point_columns_.size() && point_columns_[c].point == p; ++c) {
      const auto& col = point_columns_[c];
      if (!col.vector || col.component < 3) {
        put(shepard(*next++));
        continue;
      }
      double m2 = 0.0;
      for (int k = 0; k < world.dim; ++k) {
        const double vk = shepard(*next++);
        m2 += vk * vk;
      }
      put(std::sqrt(m2));
    }
  }
  const double down = up_ > 0 ? -1.0 : 1.0;  // from top_ towards bottom_
  for (auto& g : gauges_) {
    const std::span<const double> phi(next, g.samples.size());
    next += g.samples.size();
    g.surface = surface_elevation(g.samples, phi, vertical_, down, gauge_step_, gauge_threshold_);
    if (std::isnan(g.surface) && !g.warned) {
      g.warned = true;
      if (ranks.rank() == 0)
        world.warnings.add("probes: gauge '" + g.name + "' at " + point_text(g.at, world.dim) +
                           " finds no free surface along " + kAxis[vertical_] + " at t = " + format_real(world.time) +
                           " s (the line is dry): its column reads NaN while it stays dry");
    }
    put(wire_gauges_ ? wire_elevation(g.samples, phi, vertical_, down, gauge_step_, gauge_threshold_) : g.surface);
  }
  put_air_below(world);
  put_surface_speed(world);
  for (const auto& g : bed_gauges_) {
    const std::span<const double> phi(next, g.samples.size());
    next += g.samples.size();
    put(surface_elevation(g.samples, phi, vertical_, down, gauge_step_, gauge_threshold_));
  }
  if (runup_line_) {
    put(highest_wet_point(runup_, std::span<const double>(next, runup_.samples.size()), vertical_, gauge_threshold_));
    next += runup_.samples.size();
  }
  if (material_masses_)
    for (std::size_t m = 0; m < world.materials.size(); ++m) put(*next++);
  for (auto q : integrals_) {
    const double value = *next++;
    put(q == Quantity::max_speed ? peak_speed : value);
  }
  for (std::size_t b = 0; b < wall_bodies_.size(); ++b)
    for (int k = 0; k < world.dim; ++k) put(*next++);
  for (std::size_t b = 0; b < block_count_; ++b) {
    const bool present = world.blocks && b < world.blocks->size();
    for (int k = 0; k < world.dim; ++k)
      put(present ? world.blocks->external_force[b][k] : std::numeric_limits<double>::quiet_NaN());
  }
  for (std::size_t s = 0; s < sensors_.size(); ++s) put(*next++);
  row_ += '\n';
  if (writes_file_) file_.append(row_);
  have_last_step_ = true;
  last_step_ = world.step;
}

// The air under each surf gauge's surface (the gauges' highest surfaces are
// those of this row), sampled from the surface down: a second sum over the ranks.
void ProbesWriter::put_air_below(const World& world) {
  std::vector<std::vector<Vec3>> lines;
  std::vector<double> phi;
  const double bottom = bottom_;
  for (const auto& g : gauges_)
    if (g.air) {
      lines.push_back(std::isnan(g.surface) ? std::vector<Vec3>{}
                                            : line_samples(g.at, vertical_, g.surface, bottom, gauge_step_, 1));
      const std::size_t at = phi.size();
      phi.resize(at + lines.back().size());
      fill_fractions(sampler_, lines.back(), std::span<double>(phi).subspan(at));
    }
  if (lines.empty()) return;
  world.parallel().sum(std::span<double>(phi));
  const double min_gap = world.dp > 0.0 ? world.dp : world.kernel.h();
  const double* next = phi.data();
  for (const auto& samples : lines) {
    row_ += ',';
    row_ += format_real(air_below(samples, std::span<const double>(next, samples.size()), vertical_,
                                  gauge_threshold_, min_gap));
    next += samples.size();
  }
}

// The fastest surface particle at each surf gauge: the largest velocity
// component along the waves' direction over the fluid particles within a
// kernel support of the surface point (NaN where the gauge is dry), the
// largest over the ranks.
void ProbesWriter::put_surface_speed(const World& world) {
  if (!waves_) return;
  const auto velocity = world.fluid.vector_in_double("velocity", wide_vectors_);
  const Vec3& along = waves_->direction();
  for (const auto& g : gauges_) {
    if (!g.air) continue;
    double fastest = -std::numeric_limits<double>::infinity();
    if (!std::isnan(g.surface)) {
      Vec3 surface = g.at;
      surface[vertical_] = g.surface;
      sampler_.for_each_neighbour(
          surface, [&](Index j, const Vec3&, double) { fastest = std::max(fastest, dot(velocity[j], along)); });
    }
    fastest = world.parallel().max(fastest);
    row_ += ',';
    row_ += format_real(std::isfinite(fastest) ? fastest : std::numeric_limits<double>::quiet_NaN());
  }
}

// The bed's change between the first and the last row along the bed gauges'
// line: eroded and deposited cross-section by the trapezoidal rule in the
// horizontal distance between gauges (a segment with a dry end is left out).
std::vector<WriterResult> ProbesWriter::bed_change() const {
  std::vector<std::string> columns = {"time"};
  for (const auto& g : bed_gauges_) columns.push_back(g.name + "_bed");
  const auto series = read_series(path_, columns);
  double eroded = 0.0, deposited = 0.0;
  const std::size_t last = series[0].size() - 1;
  auto change = [&](std::size_t k) { return series[k + 1][last] - series[k + 1][0]; };
  for (std::size_t k = 0; k + 1 < bed_gauges_.size() && !series[0].empty(); ++k) {
    Vec3 step = bed_gauges_[k + 1].at - bed_gauges_[k].at;
    step[vertical_] = 0.0;
    const double a = change(k), b = change(k + 1), width = norm(step);
    if (!std::isfinite(a) || !std::isfinite(b)) continue;
    eroded += 0.5 * (std::max(0.0, -a) + std::max(0.0, -b)) * width;
    deposited += 0.5 * (std::max(0.0, a) + std::max(0.0, b)) * width;
  }
  return {{"bed_eroded_area", eroded, {}}, {"bed_deposited_area", deposited, {}}};
}

void ProbesWriter::close(const World& world) {
  if (!writes_file_) return;  // another rank's: rank 0 keeps the file and its results
  file_.close();
  if (path_.empty() || result_names().empty()) return;
  results_.clear();
  if (waves_) results_ = waves_->analyse(path_, norm(world.gravity));
  if (bed_change_ && !bed_gauges_.empty())
    for (auto& r : bed_change()) results_.push_back(std::move(r));
  std::string json = "{\n";
  for (std::size_t k = 0; k < results_.size(); ++k) {
    const WriterResult& r = results_[k];
    const std::string value = !r.text.empty()            ? "\"" + r.text + "\""
                              : std::isfinite(r.number) ? format_real(r.number)
                                                        : "null";
    json += "  \"" + r.name + "\": " + value + (k + 1 < results_.size() ? ",\n" : "\n");
  }
  json += "}\n";
  const std::string tmp = results_path_ + ".tmp";
  write_whole_file(tmp, json);
  publish(tmp, results_path_, false);
}

std::vector<std::string> ProbesWriter::result_names() const {
  std::vector<std::string> names = waves_ ? waves_->result_names() : std::vector<std::string>{};
  if (bed_change_ && !bed_gauges_.empty()) {
    names.push_back("bed_eroded_area");
    names.push_back("bed_deposited_area");
  }
  return names;
}

std::vector<std::string> ProbesWriter::files() const {
  if (path_.empty()) return {};
  if (!results_.empty()) return {path_, results_path_};
  return {path_};
}

}  // namespace talus::writers
