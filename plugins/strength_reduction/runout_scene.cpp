#include "runout_scene.hpp"

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "talus/error.hpp"

namespace talus::strength_reduction {
namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& pointer, const std::string& message) {
  throw InputError("error: " + path + ": " + pointer + ": " + message);
}

}  // namespace

RunoutTemplate read_runout_template(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("error: " + path + ": cannot read the run-out scene");
  RunoutTemplate t;
  t.path = path;
  std::stringstream text;
  text << in.rdbuf();
  try {
    t.scene = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::exception& e) {
    throw InputError("error: " + path + ": not valid JSON (" + e.what() + ")");
  }
  const auto& pipeline = t.scene.value("/pipeline"_json_pointer, nlohmann::json::array());
  bool found = false;
  for (std::size_t k = 0; k < pipeline.size() && !found; ++k)
    if (pipeline[k].is_object() && pipeline[k].value("stage", "") == "depth_integrated_sph") {
      t.stage = k;
      found = true;
    }
  if (!found) refuse(path, "/pipeline", "the hand-off needs a depth_integrated_sph stage here");
  const auto& bodies = t.scene.value("/bodies"_json_pointer, nlohmann::json::array());
  found = false;
  for (std::size_t k = 0; k < bodies.size() && !found; ++k)
    if (bodies[k].is_object() && bodies[k].value("kind", "fluid") == "fluid") {
      t.body = k;
      found = true;
    }
  if (!found) refuse(path, "/bodies", "the hand-off needs a fluid body to carry the released mass");
  const std::string where = "/bodies/" + std::to_string(t.body);
  if (!bodies[t.body].contains("material") || !bodies[t.body]["material"].is_string())
    refuse(path, where + "/material", "the released body needs a material");
  t.material = bodies[t.body]["material"].get<std::string>();
  const nlohmann::json::json_pointer rheology("/materials/" + t.material + "/rheology");
  if (!t.scene.contains(rheology) || !t.scene[rheology].is_object() ||
      t.scene[rheology].value("type", "") != "bingham")
    refuse(path, rheology.to_string(),
           "the hand-off passes the reduced joint strength as a frictional Bingham basal law (yield stress c/F_s, "
           "basal friction angle atan(tan(phi)/F_s)); give \"rheology\": {\"type\": \"bingham\", \"viscosity\": ...}");
  return t;
}

nlohmann::json runout_scene(const RunoutTemplate& t, const Handoff& h, const std::string& prefix, double cohesion,
                            double tan_friction, const std::string& description) {
  nlohmann::json s = t.scene;
  const runout::Grid& g = h.thickness;
  const double half = 0.5 * g.cell;
  s["description"] = description;
  s["domain"] = {{"dim", 2}, {"min", {g.x0 - half, g.y0 - half}}, {"max", {g.x_max() + half, g.y_max() + half}}};
  // The released body: the box of cells with a thickness, on their lattice.
  int c0 = g.ncols, c1 = -1, r0 = g.nrows, r1 = -1;
  for (int r = 0; r < g.nrows; ++r)
    for (int c = 0; c < g.ncols; ++c)
      if (g.at(c, r) > 0.0) {
        c0 = std::min(c0, c), c1 = std::max(c1, c);
        r0 = std::min(r0, r), r1 = std::max(r1, r);
      }
  auto& body = s["bodies"][t.body];
  body["dp"] = g.cell;
  body["shape"] = {{"box", {{"min", {g.x_of(c0) - half, g.y_of(r0) - half}}, {"max", {g.x_of(c1) + half, g.y_of(r1) + half}}}}};
  auto& material = s["materials"][t.material];
  material["density"] = h.density;
  material["rheology"]["yield_stress"] = cohesion;
  material["rheology"]["basal_friction_angle"] = std::atan(tan_friction) * 180.0 / std::numbers::pi;
  auto& stage = s["pipeline"][t.stage];
  stage.erase("release_thickness");
  stage["terrain"] = {{"dem", {{"file", prefix + "_terrain.asc"}}}};
  stage["thickness_raster"] = prefix + "_thickness.asc";
  stage["thickness_measured"] = "vertical";
  stage["basal_shear_raster"] = prefix + "_basal_shear.asc";
  return s;
}

}  // namespace talus::strength_reduction
