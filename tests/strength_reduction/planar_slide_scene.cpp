#include "planar_slide_scene.hpp"

#include <filesystem>
#include <fstream>
#include <numbers>

#include "process.hpp"

namespace talus::test {
namespace {

constexpr double beta = 30.0 * std::numbers::pi / 180.0;
constexpr double length = 20.0, width = 4.0, density = 1960.0, g = 9.81;

}  // namespace

nlohmann::json planar_slide(const SlabJoint& joint) {
  std::ifstream in(TALUS_SHARE_DIR "/scenes/planar_slide.json");
  nlohmann::json scene = nlohmann::json::parse(in);
  const double height = joint.thickness / std::cos(beta);
  nlohmann::json vertices = nlohmann::json::array();
  for (int k = 0; k < 8; ++k)  // the box vertex order: bit 0 down the slope, bit 1 across, bit 2 up
    vertices.push_back({k & 1 ? length * std::cos(beta) : 0.0, k & 2 ? width : 0.0,
                        (k & 1 ? -length * std::sin(beta) : 0.0) + (k & 4 ? height : 0.0)});
  for (auto& body : scene["bodies"]) {
    body["contact"]["cohesion"] = joint.cohesion;
    body["contact"]["friction_angle"] = joint.friction;
    body["contact"]["normal_stiffness"] = joint.stiffness;
    if (body["name"] == "slab") body["shape"]["polyhedron"]["vertices"] = vertices;
  }
  // The monitor in the slab's middle.
  scene["pipeline"][0]["monitors"] = {{0.5 * length * std::cos(beta), 0.5 * width,
                                       -0.5 * length * std::sin(beta) + 0.5 * height}};
  scene["outputs"] = nlohmann::json::array();
  return scene;
}

double closed_form(const SlabJoint& joint) {
  return std::tan(joint.friction * std::numbers::pi / 180.0) / std::tan(beta) +
         joint.cohesion / (density * g * joint.thickness * std::sin(beta));
}

FactorRun run_scene(const nlohmann::json& scene, const std::string& name, const std::string& options) {
  namespace fs = std::filesystem;
  const std::string base = std::string(TALUS_BINARY_DIR) + "/tests/strength_reduction";
  fs::create_directories(base);
  FactorRun r;
  r.scene = base + "/" + name + ".json";
  r.directory = base + "/" + name;
  fs::remove_all(r.directory);
  write_file(r.scene, scene.dump(1));
  const std::string summary = r.directory + ".summary.json";
  fs::remove(summary);
  const auto result = run_command(std::string(TALUS_EXE) + " run " + r.scene + " --quiet --out " + r.directory +
                                  " --summary " + summary + " " + options);
  r.exit_code = result.exit_code;
  r.output = result.output;
  if (r.exit_code == 0 && fs::exists(summary)) {
    const auto s = nlohmann::json::parse(read_file(summary));
    for (const auto& line : s["finish"]) {
      const std::string text = line.get<std::string>();
      if (std::sscanf(text.c_str(), "strength_reduction: F_s = %lf (holds at %lf, fails at %lf", &r.safety_factor,
                      &r.holds, &r.fails) == 3)
        break;
    }
  }
  return r;
}

nlohmann::json prism_block(const std::string& name, std::vector<std::pair<double, double>> section, bool fixed) {
  const std::size_t n = section.size();
  nlohmann::json vertices = nlohmann::json::array(), faces = nlohmann::json::array();
  for (int y = 0; y < 2; ++y)
    for (const auto& [x, z] : section) vertices.push_back({x, double(y), z});
  nlohmann::json front = nlohmann::json::array(), back = nlohmann::json::array();
  for (std::size_t k = 0; k < n; ++k) {
    front.push_back(k);
    back.push_back(2 * n - 1 - k);
  }
  faces.push_back(front);
  faces.push_back(back);
  for (std::size_t k = 0; k < n; ++k) faces.push_back({k, n + k, n + (k + 1) % n, (k + 1) % n});
  return {{"name", name}, {"kind", "block"}, {"density", 2038.7}, {"fixed", fixed},
          {"shape", {{"polyhedron", {{"vertices", vertices}, {"faces", faces}}}}},
          {"contact", {{"type", "mohr_coulomb"}, {"normal_stiffness", 1e9}, {"friction_angle", 20}, {"cohesion", 1e4},
                       {"damping_ratio", 0}, {"shear_softening", "none"}}}};
}

}  // namespace talus::test
