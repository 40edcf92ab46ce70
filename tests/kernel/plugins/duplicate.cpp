// Test plugin: provides a model whose name another test plugin already uses.
#include "talus/stage.hpp"

namespace {
class Other final : public talus::Stage {
 public:
  static talus::ParamSet describe() { return {"ballistic", "a second stage with a taken name"}; }
  explicit Other(const talus::ParamValues&) {}
  void setup(talus::World&) override {}
  double stable_time_step(talus::World&) override { return 1.0; }
  void advance(talus::World&, double) override {}
  talus::StagePlan plan(const talus::World&) const override { return {}; }
};
}  // namespace

TALUS_PLUGIN("talus-test-duplicate", "0.0.1", talus::model_entry<Other>("stage", "ballistic", "duplicate name"));
