// "hdf5" writer: particle fields as an H5Part time series (one file per run,
// one Step#N group per frame, x/y/z plus one dataset per scalar and NAME_0/1/2
// per vector component, TimeValue per step) that ParaView's H5Part reader
// opens with its time steps and h5py reads directly. Block states go to
// Blocks/Step#N. Layout: docs/output-formats.md. The file on disk is always a
// complete HDF5 file (see h5part_series.hpp). On several MPI ranks with
// parallel HDF5, the ranks write each frame together, each its owned rows in
// rank order, ids stored.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "h5_util.hpp"
#include "h5part_series.hpp"
#include "talus/params.hpp"
#include "talus/particles.hpp"
#include "talus/writer.hpp"
#include "xdmf_sidecar.hpp"

namespace talus::writers {

class Hdf5Writer final : public Writer {
 public:
  static ParamSet describe();
  explicit Hdf5Writer(const ParamValues& params);

  void check(const World& world) const override;
  void open(const OutputContext& context, const World& world) override;
  void write(const World& world) override;
  void close(const World& world) override;
  std::vector<std::string> files() const override;
  bool writes_on_every_rank() const override;

 private:
  // What the root attributes say about the run, taken in open().
  struct RunInfo {
    std::int64_t dim = 3;
    std::array<double, 3> lo{}, hi{}, gravity{};
    double dp = 0.0, h = 0.0;
    std::vector<std::string> bodies, materials;
  };
  void write_root(hid_t file, const char* store, const std::string& path) const;
  // This rank's rows of one frame: `shared` places them among every rank's.
  void write_particles(hid_t file, std::uint64_t index, const World& world, const ParticleStore& store,
                       const std::vector<FieldInfo>& fields, const h5::SharedRows* shared, const std::string& path);

  // One H5Part file and its optional XDMF sidecar.
  struct Output {
    H5PartSeries series;
    std::vector<FieldInfo> fields;
    std::vector<XdmfFrame> frames;  // for the sidecar
    std::string xdmf_path;          // empty: no sidecar
  };
  void start(Output& out, const std::string& name, const char* store, const World& world, bool resume);
  void append(Output& out, const World& world, const ParticleStore& store, bool with_blocks);

  ParamValues params_;
  bool boundary_ = false;
  bool xdmf_ = true;
  bool single_ = false;
  bool sync_ = true;
  OutputContext context_;
  RunInfo run_;
  Output fluid_, wall_;
  const Parallel* ranks_ = nullptr;  // several ranks that share the files; null otherwise
  bool have_last_step_ = false;
  std::uint64_t last_step_ = 0;
  std::vector<double> column_;  // one component, reused frame to frame
};

}  // namespace talus::writers
