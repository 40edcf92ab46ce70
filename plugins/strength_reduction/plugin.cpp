// The strength-reduction plugin library: the safety factor of block slopes.
#include "strength_reduction.hpp"

TALUS_PLUGIN("talus-strength-reduction", "0.1.0",
             talus::model_entry<talus::strength_reduction::StrengthReduction>(
                 "stage", "strength_reduction", "safety factor of a block slope by strength reduction"));
