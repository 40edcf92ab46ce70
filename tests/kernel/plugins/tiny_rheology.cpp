// Test plugin: a Newtonian rheology, built by the ABI tests against edited
// SDK headers or with other ABI flags (tests/kernel/plugins/CMakeLists.txt).
// It uses no libtalus function that takes a std::string, so that even the
// old-string-ABI build loads and is refused by the ABI check itself.
#include "talus/rheology.hpp"

namespace {

class TinyNewtonian final : public talus::Rheology {
 public:
  static talus::ParamSet describe() { return {}; }
  explicit TinyNewtonian(const talus::ParamValues&) {}
  bool has_apparent_viscosity() const override { return true; }
  bool is_newtonian() const override { return true; }
  double reference_viscosity() const override { return 1e-3; }
  void apparent_viscosity(std::span<const talus::Index> idx, const talus::ViscosityInputs& in,
                          double* mu) const override {
    for (const talus::Index i : idx) mu[i] = 1e-3 + 0.0 * in.shear_rate[i];
  }
};

}  // namespace

TALUS_PLUGIN(TALUS_TEST_PLUGIN_NAME, "0.0.1",
             talus::model_entry<TinyNewtonian>("rheology", "tiny_newtonian", "Newtonian test rheology"));
