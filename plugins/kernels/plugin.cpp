// The smoothing-kernel plugin: described here, tabulated by the host.
#include "cubic_spline.hpp"
#include "muller.hpp"
#include "wendland.hpp"

TALUS_PLUGIN("talus-kernels", "0.1.0",
             talus::model_entry<talus::kernels::CubicSpline>("kernel", "cubic_spline",
                                                             "cubic B-spline, support 2h (Monaghan 1992)"),
             talus::model_entry<talus::kernels::WendlandC2>("kernel", "wendland_c2",
                                                            "Wendland C2, support 2h (coastline seed)"),
             talus::model_entry<talus::kernels::WendlandC4>("kernel", "wendland_c4", "Wendland C4, support 2h"),
             talus::model_entry<talus::kernels::Muller>(
                 "kernel", "muller", "Müller 2003 poly6/spiky/viscosity set, support h (rock-fluid seed)"));
