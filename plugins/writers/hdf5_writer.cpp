#include "hdf5_writer.hpp"

#include <array>

#include "block_states.hpp"
#include "field_select.hpp"
#include "file_io.hpp"
#include "h5_ranks.hpp"
#include "h5_util.hpp"
#include "talus/output_name.hpp"
#include "talus/blocks.hpp"
#include "talus/parallel.hpp"
#include "talus/world.hpp"

namespace talus::writers {

ParamSet Hdf5Writer::describe() {
  ParamSet p{"hdf5", "particle fields as an H5Part time series (ParaView, h5py), block states alongside"};
  declare_fields_parameter(p);
  p.string("file").optional().doc("file name in the output folder; default SCENE.h5part");
  p.boolean("boundary")
      .default_value(false)
      .doc("also write the wall particles (world.boundary) to SCENE_boundary.h5part, same layout");
  p.boolean("xdmf").default_value(true).doc(
      "also write SCENE.xmf, an XDMF 2 description of the same data (ParaView's and VisIt's XDMF readers)");
  p.choice("precision", {"double", "single"})
      .default_value("double")
      .doc("storage of real fields (positions included); single halves the file size");
  p.boolean("sync").default_value(true).doc(
      "fsync each finished file before it replaces the previous one (survives a power loss)");
  check_output_name(p, "file");
  return p;
}

Hdf5Writer::Hdf5Writer(const ParamValues& params)
    : params_(params),
      boundary_(params.boolean("boundary")),
      xdmf_(params.boolean("xdmf")),
      single_(params.string("precision") == "single"),
      sync_(params.boolean("sync")) {}

namespace {
// NAME.ext -> NAME<suffix>.ext
std::string with_suffix(const std::string& name, const std::string& suffix) {
  std::string out = name;
  const auto dot = out.find_last_of('.');
  out.insert(dot == std::string::npos ? out.size() : dot, suffix);
  return out;
}
std::string with_extension(const std::string& name, const std::string& extension) {
  const auto dot = name.find_last_of('.');
  return (dot == std::string::npos ? name : name.substr(0, dot)) + extension;
}
std::string base_name(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}
}  // namespace

void Hdf5Writer::start(Output& out, const std::string& name, const char* store, const World& world, bool resume) {
  // A restart continues the existing file, dropping frames written after the
  // checkpoint by the interrupted run.
  const std::uint64_t resume_step = world.step;
  out.series.start(
      join_path(context_.directory, name), sync_,
      [this, store](hid_t f, const std::string& p) { write_root(f, store, p); }, resume ? &resume_step : nullptr,
      ranks_);
  out.frames.clear();
  for (const auto& f : out.series.resumed_frames()) out.frames.push_back({f.time, f.particles});
  out.xdmf_path = xdmf_ ? join_path(context_.directory, with_extension(name, ".xmf")) : std::string();
}

// An unknown field in the list is refused before the run writes anything.
void Hdf5Writer::check(const World& world) const { select_fields(world.fluid, params_, true); }

bool Hdf5Writer::writes_on_every_rank() const { return h5::shared_files(); }

void Hdf5Writer::open(const OutputContext& context, const World& world) {
  context_ = context;
  ranks_ = world.parallel().ranks() > 1 && writes_on_every_rank() ? &world.parallel() : nullptr;
  check_writable_directory(context.directory);
  run_ = RunInfo{world.dim,
                 {world.lo.x, world.lo.y, world.lo.z},
                 {world.hi.x, world.hi.y, world.hi.z},
                 {world.gravity.x, world.gravity.y, world.gravity.z},
                 world.dp,
                 world.h,
                 {},
                 {}};
  for (const auto& b : world.bodies) run_.bodies.push_back(b.name);
  for (const auto& m : world.materials) run_.materials.push_back(m.name);

  const std::string name = params_.has("file") ? params_.string("file") : context.scene_name + ".h5part";
  fluid_.fields = select_fields(world.fluid, params_, true);
  start(fluid_, name, "fluid", world, context.resume);
  if (boundary_) {
    wall_.fields = select_fields(world.boundary, params_, false);
    start(wall_, with_suffix(name, "_boundary"), "boundary", world, context.resume);
  }
  const auto& kept = fluid_.series.resumed_frames();
  have_last_step_ = !kept.empty();
  last_step_ = kept.empty() ? 0 : kept.back().step;
}

void Hdf5Writer::write_root(hid_t file, const char* store, const std::string& path) const {
  h5::set_attribute(file, "format", std::string_view("H5Part (Talus layout 1)"), path);
  h5::set_attribute(file, "talus_version", std::string_view(context_.talus_version), path);
  h5::set_attribute(file, "scene_name", std::string_view(context_.scene_name), path);
  h5::set_attribute(file, "scene", std::string_view(context_.scene_text), path);
  h5::set_attribute(file, "store", std::string_view(store), path);
  h5::set_attribute(file, "dim", run_.dim, path);
  h5::set_attribute(file, "domain_min", std::span<const double>(run_.lo), path);
  h5::set_attribute(file, "domain_max", std::span<const double>(run_.hi), path);
  h5::set_attribute(file, "gravity", std::span<const double>(run_.gravity), path);
  h5::set_attribute(file, "dp", run_.dp, path);
  h5::set_attribute(file, "h", run_.h, path);
  h5::set_attribute(file, "bodies", std::span<const std::string>(run_.bodies), path);
  h5::set_attribute(file, "materials", std::span<const std::string>(run_.materials), path);
  h5::set_attribute(file, "precision", std::string_view(single_ ? "single" : "double"), path);
}

void Hdf5Writer::write_particles(hid_t file, std::uint64_t index, const World& world, const ParticleStore& store,
                                 const std::vector<FieldInfo>& fields, const h5::SharedRows* shared,
                                 const std::string& path) {
  const std::size_t n = store.owned_size();
  h5::Handle group = h5::create_group(file, step_group(index), path);
  h5::set_attribute(group, "TimeValue", world.time, path);
  h5::set_attribute(group, "step", static_cast<std::uint64_t>(world.step), path);
  h5::set_attribute(group, "particles", shared ? shared->total : static_cast<std::uint64_t>(n), path);
  const auto removed = static_cast<std::uint64_t>(world.removed);
  h5::set_attribute(group, "removed", ranks_ ? ranks_->sum(removed) : removed, path);

  const hid_t real_type = single_ ? H5T_IEEE_F32LE : H5T_IEEE_F64LE;
  auto write_real = [&](const std::string& name, const double* data, const std::string& unit,
                        const std::string* vector_name, int component) {
    h5::write_dataset(group, name, real_type, H5T_NATIVE_DOUBLE, data, n, 0, path, shared);
    h5::Handle set(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose);
    h5::set_attribute(set, "unit", std::string_view(unit), path);
    if (vector_name) {
      h5::set_attribute(set, "vector", std::string_view(*vector_name), path);
      h5::set_attribute(set, "component", static_cast<std::int64_t>(component), path);
    }
  };
  // v: a span of Vec3 or of Vec3f (a field kept in float).
  auto write_vector = [&](auto v, const std::string& base, const std::string& unit, bool coordinates) {
    static const char* const axes[] = {"x", "y", "z"};
    column_.resize(n);
    for (int c = 0; c < 3; ++c) {
      for (std::size_t i = 0; i < n; ++i) column_[i] = Vec3(v[i])[c];
      // ParaView's H5Part reader takes the points from x, y, z and joins
      // NAME_0, NAME_1, NAME_2 into one vector array NAME.
      const std::string name = coordinates ? axes[c] : base + "_" + std::to_string(c);
      write_real(name, column_.data(), unit, coordinates ? nullptr : &base, c);
    }
  };

  write_vector(store.position(), "position", "m", true);
  for (const auto& f : fields) {
    switch (f.type) {
      case FieldType::scalar:
        write_real(f.name, store.scalar(f.name).data(), f.unit, nullptr, 0);
        break;
      case FieldType::vector:
        write_vector(store.vector(f.name), f.name, f.unit, false);
        break;
      case FieldType::scalar_f32: {
        const auto v = store.scalar_f32(f.name);
        column_.assign(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
        write_real(f.name, column_.data(), f.unit, nullptr, 0);
        break;
      }
      case FieldType::vector_f32:
        write_vector(store.vector_f32(f.name), f.name, f.unit, false);
        break;
      case FieldType::integer: {
        h5::write_dataset(group, f.name, H5T_STD_I32LE, H5T_NATIVE_INT32, store.integer(f.name).data(), n, 0, path,
                          shared);
        h5::Handle set(H5Dopen2(group, f.name.c_str(), H5P_DEFAULT), H5Dclose);
        h5::set_attribute(set, "unit", std::string_view(f.unit), path);
        break;
      }
      case FieldType::id: {
        h5::write_dataset(group, f.name, H5T_STD_U64LE, H5T_NATIVE_UINT64, store.ids().data(), n, 0, path, shared);
        break;
      }
    }
  }
}

void Hdf5Writer::append(Output& out, const World& world, const ParticleStore& store, bool with_blocks) {
  const std::uint64_t mine = store.owned_size();
  h5::Handle transfer;
  h5::SharedRows shared;
  if (ranks_) {
    transfer = h5::collective_transfer(out.series.path());
    shared = {ranks_->sum(mine), ranks_->sum_before(mine), transfer.get()};
  }
  auto rows = [&](hid_t file, std::uint64_t index, const std::string& path) {
    write_particles(file, index, world, store, out.fields, ranks_ ? &shared : nullptr, path);
  };
  // Every rank holds the blocks whole: rank 0 writes them.
  H5PartSeries::FrameWriter blocks;
  if (with_blocks && world.blocks && world.blocks->size() > 0)
    blocks = [&](hid_t file, std::uint64_t index, const std::string& path) {
      write_block_states(file, *world.blocks, index, world.time, world.step, path);
    };
  out.series.append(rows, blocks);
  out.frames.push_back({world.time, ranks_ ? shared.total : mine});
  if (out.xdmf_path.empty() || (ranks_ && ranks_->rank() != 0)) return;
  // Rewritten after the HDF5 file it describes is in place: it never lists a
  // frame that file lacks.
  write_whole_file(out.xdmf_path + ".tmp", build_xdmf(base_name(out.series.path()), out.frames, out.fields, single_));
  publish(out.xdmf_path + ".tmp", out.xdmf_path, sync_);
}

void Hdf5Writer::write(const World& world) {
  // The host may ask twice for the same state (last frame at the end of the
  // run, the first one after a restart): one frame per step.
  if (have_last_step_ && world.step == last_step_) return;
  append(fluid_, world, world.fluid, true);
  if (boundary_) append(wall_, world, world.boundary, false);
  have_last_step_ = true;
  last_step_ = world.step;
}

void Hdf5Writer::close(const World& /*world*/) {
  fluid_.series.finish();
  if (boundary_) wall_.series.finish();
}

std::vector<std::string> Hdf5Writer::files() const {
  // The host names files.back() as the run's newest output: the particles.
  std::vector<std::string> out;
  auto add = [&](const Output& o) {
    if (o.series.frames() == 0) return;
    if (!o.xdmf_path.empty()) out.push_back(o.xdmf_path);
    out.push_back(o.series.path());
  };
  if (boundary_) add(wall_);
  add(fluid_);
  return out;
}

}  // namespace talus::writers
