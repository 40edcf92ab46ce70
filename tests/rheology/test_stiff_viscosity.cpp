// The wcsph option stiff_viscosity: point_implicit (plugins/wcsph/viscosity_passes.cpp): each particle's
// acceleration divided by 1 + dt D_i, the diagonal of a backward-Euler viscous step. Checked on the flat sediment
// bed of tests/sph/test_sediment.cpp with the seed's uncapped HBP plug (tau_y m, ~1e4 Pa s at the bed's base):
//  - the step is the acoustic one, where the explicit viscous bound makes it ~40x smaller;
//  - equilibria are kept: the bed stays at rest and unyielded below its surface, as the capped explicit bed does;
//  - the option is refused where it does not apply (arithmetic pair viscosity).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <unordered_map>

#include "../sph/sph_world.hpp"
#include "hbp.hpp"
#include "hbp_formula.hpp"
#include "newtonian.hpp"
#include "talus/error.hpp"

namespace {

using sph_test::SphWorld;
using talus::Vec3;

constexpr double kDp = 0.01, kHOverDp = 1.5, kC0 = 20.0, kCourant = 0.2;
constexpr double kRhoW = 1029.0, kRhoS = 1922.0, kBed = 0.05, kWater = 0.05, kLength = 0.4;

// Coastline seed Table 3 sediment, Drucker-Prager on the effective pressure, no max_viscosity cap.
const char* kSediment = R"({"yield": "drucker_prager", "cohesion": 1, "friction_angle": 35,
  "yield_pressure": "effective", "pore_fluid_density": 1029, "regularisation": 100, "power_index": 1,
  "consistency": 0.126})";

template <class M>
void set_rheology(SphWorld& s, int material, const std::string& json) {
  auto r = std::make_unique<M>(talus::params_from_json(M::describe(), json));
  s.world.materials[material].rheology = r.get();
  s.models.push_back(std::move(r));
}

// Tank [0, 0.4] x [0, 0.3]: 0.05 m of sediment under 0.05 m of sea water at hydrostatic rest.
struct Bed {
  SphWorld s{2, {0, 0, 0}, {kLength, 0.3, 0}, kDp, kHOverDp};
  int water = -1, sediment = -1;

  explicit Bed(const std::string& stage_extra) {
    water = s.water(kC0, kRhoW, "seawater");
    sediment = s.water(kC0, kRhoS, "sediment");
    set_rheology<talus::rheology::Newtonian>(s, water, R"({"viscosity": 1.08e-3})");
    set_rheology<talus::rheology::Hbp>(s, sediment, kSediment);
    s.fluid_box(sediment, {0, 0, 0}, {kLength, kBed, 0}, true);
    s.fluid_box(water, {0, kBed, 0}, {kLength, kBed + kWater, 0}, true);
    auto p = s.world.fluid.scalar("pressure");  // the bed also carries the water above it
    auto rho = s.world.fluid.scalar("density");
    const auto mat = s.world.fluid.material();
    for (std::size_t i = 0; i < p.size(); ++i)
      if (mat[i] == sediment) {
        p[i] += kRhoW * 9.81 * kWater;
        rho[i] = s.world.materials[sediment].eos->density_at(p[i]);
      }
    s.dbc_wall(R"({"box_walls": {"min": [0, 0], "max": [0.4, 0.3], "open": ["+y"]}})", water, ", \"layers\": 3");
    s.make_stage(R"({"viscosity": "laminar", "density_diffusion": "none", "courant": 0.2)" + stage_extra + "}");
  }
};

TEST(StiffViscosity, PointImplicitStepsAtTheAcousticLimitWithTheUncappedPlug) {
  Bed explicit_bed(R"(, "viscosity_mean": "harmonic")");
  Bed implicit_bed(R"(, "viscosity_mean": "harmonic", "stiff_viscosity": "point_implicit")");
  const double dt_explicit = explicit_bed.s.stage->stable_time_step(explicit_bed.s.world);
  const double dt_implicit = implicit_bed.s.stage->stable_time_step(implicit_bed.s.world);
  const double acoustic = kCourant * kHOverDp * kDp / kC0;
  // At rest (|D| = 0) the plug viscosity tau_y(p') m: ~1e4 Pa s at the base, C h^2 rho/mu ~ 4e-6 s.
  EXPECT_LT(dt_explicit, 0.1 * acoustic) << "explicit dt " << dt_explicit;
  EXPECT_GE(dt_implicit, 0.9 * acoustic) << "point-implicit dt " << dt_implicit;
}

TEST(StiffViscosity, PointImplicitKeepsTheBedAtRestAndUnyielded) {
  Bed bed(R"(, "viscosity_mean": "harmonic", "stiff_viscosity": "point_implicit")");
  auto& s = bed.s;
  const auto ids0 = s.world.fluid.ids();
  const auto x0 = s.world.fluid.position();
  std::unordered_map<std::uint64_t, Vec3> start;
  for (std::size_t i = 0; i < ids0.size(); ++i) start[ids0[i]] = x0[i];
  const talus::rheology::YieldStress dp =
      talus::rheology::YieldStress::make(talus::rheology::YieldModel::drucker_prager, 0.0, 1.0, 35.0);
  double worst_speed = 0.0, worst_shift = 0.0, highest = 0.0;
  std::size_t yielded_deep = 0, deep = 0, steps = 0;
  while (s.world.time < 0.5) {
    s.step();
    ++steps;
    const auto x = s.world.fluid.position();
    const auto v = s.world.fluid.vector("velocity");
    const auto ids = s.world.fluid.ids();
    const auto mat = s.world.fluid.material();
    const auto mu = s.world.fluid.scalar("mu_eff");
    const auto gd = s.world.fluid.scalar("shear_rate");
    const auto p = s.world.fluid.scalar("pressure");
    const auto rho = s.world.fluid.scalar("density");
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (mat[i] != bed.sediment) continue;
      worst_speed = std::max(worst_speed, talus::norm(v[i]));
      worst_shift = std::max(worst_shift, talus::norm(x[i] - start.at(ids[i])));
      highest = std::max(highest, x[i].y);
      if (x[i].y < kBed - 2 * kDp && s.world.step % 20 == 0) {  // below the bed's top two rows
        ++deep;
        const double tau_y = dp.at(talus::rheology::effective_pressure(p[i], rho[i], kRhoW));
        if (mu[i] * gd[i] >= tau_y) ++yielded_deep;
      }
    }
  }
  ASSERT_GT(deep, 0u);
  // The same bounds as the capped explicit bed (tests/sph/test_sediment.cpp): mm/s of acoustic settling, where a
  // bed that yields or mixes moves at 0.1 - 1 m/s; at the acoustic step, 0.5 s is ~3400 steps.
  EXPECT_LT(steps, 4000u);
  EXPECT_LT(worst_speed, 0.01) << "the bed moved";
  EXPECT_LT(worst_shift, 0.1 * kDp) << "a bed particle drifted";
  EXPECT_LT(highest, kBed) << "a sediment particle left the bed for the water";
  EXPECT_EQ(yielded_deep, 0u) << "of " << deep << " samples below the surface";
}

TEST(StiffViscosity, PointImplicitNeedsTheHarmonicPairViscosity) {
  EXPECT_THROW(Bed(R"(, "stiff_viscosity": "point_implicit")"), talus::InputError);
}

}  // namespace
