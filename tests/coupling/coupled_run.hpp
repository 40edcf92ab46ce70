// Runs a scene through the host exactly as `talus run` does (plugins from the
// build, validation, setup, time loop), with the scene's JSON edited first,
// and gives the test the World afterwards.
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "plugin_registry.hpp"
#include "scene.hpp"
#include "simulation.hpp"
#include "talus/blocks.hpp"
#include "talus/world.hpp"

namespace coupling_test {

using nlohmann::json;

inline json read_scene(const std::string& name) {
  std::ifstream in(std::string(TALUS_SHARE_DIR) + "/scenes/" + name);
  return json::parse(in);
}

inline std::string scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::path(TALUS_BINARY_DIR) / "tests" / "coupling_scratch" / name;
  std::filesystem::create_directories(dir);
  return dir.string();
}

struct CoupledRun {
  talus::PluginRegistry registry;
  std::unique_ptr<talus::Simulation> sim;
  std::string dir;

  // Writes `scene` as NAME.json in a scratch folder and builds the simulation.
  CoupledRun(const json& scene, const std::string& name) : dir(scratch_dir(name)) {
    const std::string path = dir + "/" + name + ".json";
    std::ofstream(path) << scene.dump(1);
    registry.add_default_locations();
    sim = std::make_unique<talus::Simulation>(registry, talus::load_scene(path, registry));
  }
  int run() {
    talus::RunOptions o;
    o.output_directory = dir + "/out";
    o.quiet = true;
    return sim->run(o);
  }
  talus::World& world() { return sim->world(); }
  std::size_t block(const std::string& name) const {
    const auto& b = *sim->world().blocks;
    for (std::size_t i = 0; i < b.size(); ++i)
      if (b.name[i] == name) return i;
    return b.size();
  }
};

inline talus::Vec3 fluid_momentum(const talus::World& w) {
  const auto v = w.fluid.vector("velocity");
  const auto m = w.fluid.scalar("mass");
  talus::Vec3 p{};
  for (std::size_t i = 0; i < v.size(); ++i) p += v[i] * m[i];
  return p;
}

}  // namespace coupling_test
