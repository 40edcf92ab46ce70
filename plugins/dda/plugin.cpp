// The DDA stage plugin.
#include "dda_stage.hpp"
#include "talus/plugin.hpp"

TALUS_PLUGIN("talus-dda", "0.1.0",
             talus::model_entry<talus::dda::DdaStage>("stage", "dda",
                                                      "explicit 3D DDA: polyhedral blocks, frictional contacts"));
