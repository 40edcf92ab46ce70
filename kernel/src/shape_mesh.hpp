// The triangle mesh a scene's `mesh` shape names, with the shape's scale and
// offset applied: what the lattice fills and what the estimate measures.
#pragma once

#include "talus/mesh.hpp"
#include "talus/params.hpp"

namespace talus {

TriangleMesh scaled_mesh(const ParamValues& mesh_shape);

}  // namespace talus
