#include "dda_test_world.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include <nlohmann/json.hpp>

#include "mohr_coulomb.hpp"
#include "penalty_coulomb.hpp"
#include "talus/geometry.hpp"
#include "talus/motion.hpp"

namespace talus::dda::test {

ParamSet block_body_params() {
  ParamSet p{"block", "a rigid block body (test copy of the scene's declaration)"};
  p.string("name").doc("body name");
  p.choice("kind", {"block"}).doc("body kind");
  p.real("density").unit("kg/m^3").greater_than(0.0).doc("density");
  declare_shape(p);
  p.boolean("fixed").default_value(false).doc("never moves");
  p.vector("velocity").unit("m/s").default_value(std::vector<double>{0.0, 0.0, 0.0}).doc("initial velocity");
  p.vector("angular_velocity").unit("rad/s").default_value(std::vector<double>{0.0, 0.0, 0.0}).doc("initial angular velocity");
  p.string("clump").optional().doc("blocks with the same clump name move as one rigid body");
  PrescribedMotion::declare(p);
  return p;
}

BlockScene::BlockScene(Vec3 gravity) {
  world.dim = 3;
  world.gravity = gravity;
  world.lo = {-100, -100, -100};
  world.hi = {100, 100, 100};
}

int BlockScene::add_block(const std::string& body_json, const std::string& contact_json) {
  Body body;
  body.kind = BodyKind::block;
  const std::string pointer = "/bodies/" + std::to_string(world.bodies.size());
  body.params = params_from_json(block_body_params(), body_json, 3, "test.json");
  body.name = body.params.string("name");
  // The contact model: "type" selects the class, the rest are its parameters.
  auto contact = nlohmann::json::parse(contact_json);
  const bool mohr = contact.at("type") == "mohr_coulomb";
  contact.erase("type");
  const std::string params = contact.dump();
  if (mohr)
    models.push_back(std::make_unique<contact::MohrCoulomb>(
        params_from_json(contact::MohrCoulomb::describe(), params, 3, "contact.json")));
  else
    models.push_back(std::make_unique<contact::PenaltyCoulomb>(
        params_from_json(contact::PenaltyCoulomb::describe(), params, 3, "contact.json")));
  body.contact = models.back().get();
  world.bodies.push_back(std::move(body));
  return static_cast<int>(world.bodies.size()) - 1;
}

DdaStage& BlockScene::start(const std::string& stage_json) {
  stage = std::make_unique<DdaStage>(params_from_json(DdaStage::describe(), stage_json, 3, "stage.json"));
  stage->setup(world);
  return *stage;
}

void BlockScene::run_steps(long n, double dt) {
  for (long k = 0; k < n; ++k) {
    const double h = dt > 0.0 ? dt : stage->stable_time_step(world);
    stage->advance(world, h);
    world.time += h;
    ++world.step;
  }
}

void BlockScene::run_until(double t_end) {
  while (world.time < t_end - 1e-12) {
    const double h = std::min(stage->stable_time_step(world), t_end - world.time);
    stage->advance(world, h);
    world.time += h;
    ++world.step;
  }
}

std::string contact(double phi_deg, double damping, const char* type,
                    const std::string& extra) {
  return std::string("{\"type\": \"") + type + "\", \"normal_stiffness\": 1e8, \"friction_angle\": " +
         std::to_string(phi_deg) + ", \"damping_ratio\": " + std::to_string(damping) + extra + "}";
}

std::string block(const std::string& name, const std::string& shape, const std::string& extra) {
  return "{\"name\": \"" + name + "\", \"kind\": \"block\", \"density\": 2500, \"shape\": " + shape + extra + "}";
}

std::string box(Vec3 lo, Vec3 hi) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "{\"box\": {\"min\": [%.17g, %.17g, %.17g], \"max\": [%.17g, %.17g, %.17g]}}", lo.x,
                lo.y, lo.z, hi.x, hi.y, hi.z);
  return buf;
}

std::string rotated_box_json(Vec3 lo, Vec3 hi, double angle_deg, Vec3 pivot) {
  const double a = angle_deg * std::numbers::pi / 180.0, c = std::cos(a), s = std::sin(a);
  std::string v = "[";
  for (int k = 0; k < 8; ++k) {
    const Vec3 p{(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z};
    const Vec3 d = p - pivot;
    // Rotation about +y by -angle: a slope rising towards -x, descending along +x.
    const Vec3 r{c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
    const Vec3 q = pivot + r;
    char buf[128];
    std::snprintf(buf, sizeof buf, "%s[%.17g,%.17g,%.17g]", k ? "," : "", q.x, q.y, q.z);
    v += buf;
  }
  v += "]";
  return "{\"polyhedron\": {\"vertices\": " + v +
         ", \"faces\": [[0,2,3,1],[4,5,7,6],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]]}}";
}

}  // namespace talus::dda::test
