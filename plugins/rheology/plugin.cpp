// The rheology plugin library: Newtonian, Bingham, Coulomb, Voellmy, HBP, power law, Herschel-Bulkley.
#include "bingham.hpp"
#include "coulomb.hpp"
#include "hbp.hpp"
#include "power_law.hpp"
#include "newtonian.hpp"
#include "voellmy.hpp"

TALUS_PLUGIN("talus-rheology", "0.1.0",
             talus::model_entry<talus::rheology::Newtonian>(
                 "rheology", "newtonian", "Newtonian fluid; laminar basal shear 3 mu v / h"),
             talus::model_entry<talus::rheology::Bingham>(
                 "rheology", "bingham", "Bingham fluid, Papanastasiou-regularised; infinite-landslide basal shear"),
             talus::model_entry<talus::rheology::Coulomb>(
                 "rheology", "coulomb", "frictional basal stress with pore pressure ratio (depth-integrated)"),
             talus::model_entry<talus::rheology::Voellmy>(
                 "rheology", "voellmy", "Voellmy friction + turbulence basal stress (depth-integrated)"),
             talus::model_entry<talus::rheology::Hbp>(
                 "rheology", "hbp", "Herschel-Bulkley-Papanastasiou sediment; constant or Mohr-Coulomb/Drucker-Prager yield"),
             talus::model_entry<talus::rheology::PowerLaw>("rheology", "power_law", "power-law fluid K |D|^(n-1)"),
             talus::model_entry<talus::rheology::HerschelBulkley>(
                 "rheology", "herschel_bulkley", "Herschel-Bulkley fluid, bi-viscosity below the yield stress"));
