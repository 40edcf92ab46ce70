// The contact-model plugin: joint laws for the DDA stage.
#include "mohr_coulomb.hpp"
#include "penalty_coulomb.hpp"
#include "talus/plugin.hpp"

TALUS_PLUGIN("talus-contact", "0.1.0",
             talus::model_entry<talus::contact::PenaltyCoulomb>(
                 "contact", "penalty_coulomb", "DDA penalty springs, Coulomb friction, contact damping"),
             talus::model_entry<talus::contact::MohrCoulomb>(
                 "contact", "mohr_coulomb", "penalty springs with cohesion and tensile strength that break"));
