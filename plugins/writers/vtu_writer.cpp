#include "vtu_writer.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "field_select.hpp"
#include "file_io.hpp"
#include "talus/output_name.hpp"
#include "talus/world.hpp"

namespace talus::writers {

ParamSet VtuWriter::describe() {
  ParamSet p{"vtu", "VTK XML files: one .vtu per frame and a .pvd collection (ParaView)"};
  declare_fields_parameter(p);
  p.string("prefix").optional().doc("file name prefix in the output folder; default the scene name");
  p.boolean("boundary")
      .default_value(false)
      .doc("also write the wall particles (world.boundary) as a second series PREFIX_boundary");
  p.choice("encoding", {"binary", "ascii"})
      .default_value("binary")
      .doc("inline data: base64 binary (compact, exact) or ascii text (readable, larger)");
  p.choice("precision", {"double", "single"})
      .default_value("double")
      .doc("storage of real fields (positions included): Float64 or Float32");
  p.boolean("sync").default_value(true).doc(
      "fsync each finished file before it is renamed into place (survives a power loss)");
  check_output_name(p, "prefix");
  return p;
}

VtuWriter::VtuWriter(const ParamValues& params)
    : params_(params),
      options_{params.string("encoding") == "binary", params.string("precision") == "single"},
      boundary_(params.boolean("boundary")),
      sync_(params.boolean("sync")) {}

void VtuWriter::start(Series& series, const std::string& prefix, const World& world, bool resume) {
  series.prefix = prefix;
  series.entries.clear();
  if (!resume) return;
  // Restart: keep the frames up to the checkpoint's time.
  std::ifstream in(join_path(directory_, prefix + ".pvd"));
  if (!in) return;
  std::stringstream text;
  text << in.rdbuf();
  for (auto& e : parse_pvd(text.str()))
    if (e.time <= world.time) series.entries.push_back(std::move(e));
}

// An unknown field in the list is refused before the run writes anything.
void VtuWriter::check(const World& world) const { select_fields(world.fluid, params_, true); }

void VtuWriter::open(const OutputContext& context, const World& world) {
  directory_ = context.directory;
  check_writable_directory(directory_);
  const std::string prefix = params_.has("prefix") ? params_.string("prefix") : context.scene_name;
  fluid_.fields = select_fields(world.fluid, params_, true);
  start(fluid_, prefix, world, context.resume);
  if (boundary_) {
    wall_.fields = select_fields(world.boundary, params_, false);
    start(wall_, prefix + "_boundary", world, context.resume);
  }
  // After a restart the host may write the checkpoint's state again.
  have_last_step_ = !fluid_.entries.empty() && fluid_.entries.back().time == world.time;
  last_step_ = world.step;
}

void VtuWriter::write_frame(Series& series, const ParticleStore& store, const World& world) {
  char number[32];
  std::snprintf(number, sizeof number, "_%06zu.vtu", series.entries.size());
  const std::string name = series.prefix + number;
  const std::string path = join_path(directory_, name);

  build_vtu(text_, store, series.fields, world.time, world.step, options_, scratch_);
  write_whole_file(path + ".tmp", text_);
  publish(path + ".tmp", path, sync_);

  // The collection is rewritten only once the frame it adds is in place.
  series.entries.push_back({world.time, name});
  const std::string pvd = join_path(directory_, series.prefix + ".pvd");
  try {
    write_whole_file(pvd + ".tmp", build_pvd(series.entries));
    publish(pvd + ".tmp", pvd, sync_);
  } catch (...) {
    series.entries.pop_back();
    throw;
  }
}

void VtuWriter::write(const World& world) {
  if (have_last_step_ && world.step == last_step_) return;
  write_frame(fluid_, world.fluid, world);
  if (boundary_) write_frame(wall_, world.boundary, world);
  have_last_step_ = true;
  last_step_ = world.step;
}

std::vector<std::string> VtuWriter::files() const {
  // The host names files.back() as the run's newest output: the particles.
  std::vector<std::string> out;
  if (boundary_ && !wall_.entries.empty()) out.push_back(join_path(directory_, wall_.prefix + ".pvd"));
  if (!fluid_.entries.empty()) out.push_back(join_path(directory_, fluid_.prefix + ".pvd"));
  return out;
}

}  // namespace talus::writers
