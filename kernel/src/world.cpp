#include "talus/world.hpp"

#include "talus/blocks.hpp"

namespace talus {

const char* to_string(BodyKind kind) {
  switch (kind) {
    case BodyKind::fluid: return "fluid";
    case BodyKind::wall: return "wall";
    case BodyKind::block: return "block";
  }
  return "?";
}

Parallel::~Parallel() = default;

Parallel World::serial_;

World::World() = default;
World::~World() = default;

void World::refresh_material_index() {
  // Clear rather than rebuild, so the index vectors keep their capacity; after
  // a release, each is allocated once at its size (no growth by doubling).
  material_index_.resize(materials.size());
  const auto mat = fluid.material();
  auto listed = [&](std::size_t i) { return mat[i] >= 0 && static_cast<std::size_t>(mat[i]) < materials.size(); };
  std::vector<std::size_t> count(materials.size(), 0);
  for (std::size_t i = 0; i < fluid.size(); ++i)
    if (listed(i)) ++count[mat[i]];
  for (std::size_t m = 0; m < materials.size(); ++m) {
    material_index_[m].clear();
    material_index_[m].reserve(count[m]);
  }
  for (std::size_t i = 0; i < fluid.size(); ++i)
    if (listed(i)) material_index_[mat[i]].push_back(static_cast<Index>(i));
}

int World::find_material(std::string_view name) const {
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == name) return static_cast<int>(i);
  return -1;
}

int World::find_body(std::string_view name) const {
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace talus
