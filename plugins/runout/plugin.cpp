// The run-out plugin library: the depth-integrated SPH stage.
#include "depth_integrated_sph.hpp"

TALUS_PLUGIN("talus-runout", "0.1.0",
             talus::model_entry<talus::runout::DepthIntegratedSph>(
                 "stage", "depth_integrated_sph", "depth-integrated SPH run-out over terrain (plan view)"));
