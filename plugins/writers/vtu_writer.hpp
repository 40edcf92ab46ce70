// "vtu" writer: one VTK XML UnstructuredGrid file per frame (PREFIX_NNNNNN.vtu)
// and a PREFIX.pvd collection listing every frame with its time, for users
// who want plain ParaView files. Every file is written to NAME.tmp and
// renamed, the .pvd rewritten the same way after each frame, so ParaView
// never sees a half-written frame or a collection naming a missing file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "talus/params.hpp"
#include "talus/particles.hpp"
#include "talus/writer.hpp"
#include "vtu_format.hpp"

namespace talus::writers {

class VtuWriter final : public Writer {
 public:
  static ParamSet describe();
  explicit VtuWriter(const ParamValues& params);

  void check(const World& world) const override;
  void open(const OutputContext& context, const World& world) override;
  void write(const World& world) override;
  std::vector<std::string> files() const override;

 private:
  struct Series {
    std::string prefix;  // file name prefix in the output folder
    std::vector<FieldInfo> fields;
    std::vector<PvdEntry> entries;  // frames listed in the .pvd
  };
  void start(Series& series, const std::string& prefix, const World& world, bool resume);
  void write_frame(Series& series, const ParticleStore& store, const World& world);

  ParamValues params_;
  VtuOptions options_;
  bool boundary_ = false;
  bool sync_ = true;
  std::string directory_;
  Series fluid_, wall_;
  bool have_last_step_ = false;
  std::uint64_t last_step_ = 0;
  std::string text_;  // the document being built, reused
  VtuScratch scratch_;
};

}  // namespace talus::writers
