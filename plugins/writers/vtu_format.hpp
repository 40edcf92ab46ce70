// VTK XML text for particles: an UnstructuredGrid (.vtu) with one VTK_VERTEX
// cell per particle (so ParaView's Threshold and Extract filters work per
// particle) and the .pvd collection that lists the frames with their times.
// Data arrays are inline, either "binary" (base64 of a UInt64 byte count
// followed by the little-endian data, one base64 stream, as VTK writes it) or
// "ascii". Layout: docs/output-formats.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "talus/particles.hpp"

namespace talus::writers {

struct VtuOptions {
  bool binary = true;   // base64 inline data; false: ascii
  bool single = false;  // Float32 for real fields
};

// Reused buffers so that a frame does not allocate once sizes settle.
struct VtuScratch {
  std::vector<float> reals;
  std::vector<std::int32_t> indices32;
  std::vector<std::int64_t> indices;
  std::vector<std::uint8_t> types;
};

// Replaces `out` with the .vtu document of `store`.
void build_vtu(std::string& out, const ParticleStore& store, const std::vector<FieldInfo>& fields, double time,
               std::uint64_t step, const VtuOptions& options, VtuScratch& scratch);

struct PvdEntry {
  double time = 0.0;
  std::string file;  // relative to the .pvd
};
std::string build_pvd(const std::vector<PvdEntry>& entries);
// Reads back the entries of a .pvd this module wrote (restart); empty on any
// problem.
std::vector<PvdEntry> parse_pvd(const std::string& text);

// Shortest text that reads back to the same double.
std::string format_real(double v);

}  // namespace talus::writers
