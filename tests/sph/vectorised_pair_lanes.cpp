// The mutual pass's lane loop instantiated with the fluid terms of a scene:
// compiled by vectorised_pair_lanes.cmake, whose test reads the compiler's
// vectorisation report. TERMS 1: the dam break's set (pressure, artificial
// viscosity, continuity, Fourtakas diffusion); TERMS 2: laminar viscosity
// with continuity and Molteni diffusion; TERMS 3: the dam break's set on a
// fluid in float (mixed precision); TERMS 4: the same on a fluid of one
// material and one mass (sph::UniformNeighbourFields); TERMS 5: the same
// from neighbour records (sph::GatheredNeighbourFields), as the dam break
// runs in mixed precision; TERMS 6: the dam break's set from records of
// doubles, as it runs in double.
#include "fluid_sums.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/sph/mutual_pass.hpp"

namespace talus {

#if TERMS >= 3 && TERMS <= 5
using Stored = float;
#else
using Stored = double;
#endif
#if TERMS >= 5
using Fields = sph::GatheredNeighbourFields<Stored>;
#elif TERMS == 4
using Fields = sph::UniformNeighbourFields<Stored>;
#else
using Fields = sph::NeighbourFields<Stored>;
#endif

// With the wcsph stage's own i-state and sums, as its force pass has them.
void evaluate_lanes(sph::PairLanes& lanes, const KernelTable& kernel, wcsph::FluidSums& sums,
                    sph::FluidReactions<Stored> out, const Fields& nb, const double* mu_of_material) {
  const sph::PressureForce pressure{nb};
  const sph::Continuity continuity{nb};
#if TERMS == 2
  const sph::LaminarViscosity<false> viscosity{nb, mu_of_material, 1e-6};
  const sph::DensityDiffusion<false> diffusion{nb, 0.1, {0, 0, -9.81}};
#else
  (void)mu_of_material;
  const sph::ArtificialViscosity viscosity{nb, 0.01};
  const sph::DensityDiffusion<true, Fields> diffusion{nb, 0.1, {0, 0, -9.81}};
#endif
  sph::run_lanes<false, true>(lanes, kernel, 0.01, sums, out, pressure, viscosity, continuity, diffusion);
}

}  // namespace talus
