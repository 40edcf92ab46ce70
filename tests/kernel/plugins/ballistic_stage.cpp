// Test plugin: a stage that moves fluid particles ballistically (x += v dt,
// v += g dt) with a fixed stable step. It exercises the host's time loop,
// outputs, checkpoints and signal handling without any SPH physics.
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "talus/stage.hpp"
#include "talus/world.hpp"

namespace {

class Ballistic final : public talus::Stage {
 public:
  static talus::ParamSet describe() {
    talus::ParamSet p{"ballistic", "free flight of fluid particles (test stage)"};
    p.real("dt").unit("s").greater_than(0.0).default_value(1e-3).doc("time step");
    p.real("sleep").unit("s").min(0.0).default_value(0.0).doc("wall time to sleep per step (signal tests)");
    p.real("nan_at").unit("s").min(0.0).optional().doc("make particle 0's velocity NaN at this time (error tests)");
    p.real("scratch_bytes").min(0.0).default_value(0.0).doc("bytes of scratch to allocate at setup (out-of-memory tests)");
    p.string("body_field").default_value("velocity").doc("the start-state field it reads from the bodies (host tests)");
    return p;
  }
  explicit Ballistic(const talus::ParamValues& v)
      : dt_(v.real("dt")), sleep_(v.real("sleep")), nan_at_(v.has("nan_at") ? v.real("nan_at") : -1.0),
        scratch_bytes_(v.real("scratch_bytes")), body_field_(v.string("body_field")) {}

  talus::StageParts parts(const talus::World&) const override { return {{}, {}, {body_field_}}; }
  void setup(talus::World& world) override {
    world.fluid.require({"acceleration", talus::FieldType::vector, "m/s^2", true, false});
    if (scratch_bytes_ > 0) scratch_.resize(static_cast<std::size_t>(scratch_bytes_));
  }
  double stable_time_step(talus::World&) override { return dt_; }
  void advance(talus::World& world, double dt) override {
    auto x = world.fluid.position();
    auto u = world.fluid.vector("velocity");
    auto a = world.fluid.vector("acceleration");
    for (std::size_t i = 0; i < world.fluid.size(); ++i) {
      a[i] = world.gravity;
      u[i] += a[i] * dt;
      x[i] += u[i] * dt;
    }
    if (nan_at_ >= 0 && world.time + dt >= nan_at_ && world.fluid.size()) u[0].x = std::nan("");
    if (sleep_ > 0) std::this_thread::sleep_for(std::chrono::duration<double>(sleep_));
    ++steps_;
  }
  talus::StagePlan plan(const talus::World&) const override {
    return {{"kick-drift over fluid particles"}, {"velocity", "position"}, {"velocity", "position", "acceleration"}, {}};
  }
  std::string save_state() const override { return std::to_string(steps_); }
  void load_state(std::string_view s) override { steps_ = std::stoull(std::string(s)); }

 private:
  double dt_, sleep_, nan_at_, scratch_bytes_;
  std::string body_field_;
  std::vector<char> scratch_;
  unsigned long long steps_ = 0;
};

}  // namespace

TALUS_PLUGIN("talus-test-good", "1.2.3",
             talus::model_entry<Ballistic>("stage", "ballistic", "free flight of fluid particles (test stage)"));
