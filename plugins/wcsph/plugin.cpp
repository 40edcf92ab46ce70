// The wcsph stage plugin.
#include "wcsph_stage.hpp"

TALUS_PLUGIN("talus-wcsph", "0.1.0",
             talus::model_entry<talus::wcsph::WcsphStage>("stage", "wcsph",
                                                          "weakly compressible SPH for water, 2D and 3D"));
