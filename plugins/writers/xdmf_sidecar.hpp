// XDMF (version 2) sidecar of the H5Part file: SCENE.xmf describes every
// Step#N group as a particle grid of a temporal collection, so that readers
// other than ParaView's H5Part reader (ParaView's and VisIt's XDMF readers)
// open the same data. Polyvertex topology with one node per element (ParaView
// needs the topology spelled out), data referenced by a path relative to the
// .xmf (the two files move together). Layout: docs/output-formats.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "talus/particles.hpp"

namespace talus::writers {

struct XdmfFrame {
  double time = 0.0;
  std::uint64_t particles = 0;
};

// The .xmf text for `frames` (frame k is group Step#k of `h5_file`).
std::string build_xdmf(const std::string& h5_file, const std::vector<XdmfFrame>& frames,
                       const std::vector<FieldInfo>& fields, bool single);

}  // namespace talus::writers
