// The equation-of-state plugin.
#include "ideal_gas.hpp"
#include "linear.hpp"
#include "tait.hpp"

TALUS_PLUGIN("talus-eos", "0.1.0",
             talus::model_entry<talus::eos::Tait>("eos", "tait", "Tait EOS p = B((rho/rho0)^gamma - 1) (coastline seed)"),
             talus::model_entry<talus::eos::Linear>("eos", "linear", "linear EOS p = k (rho - rho0) (rock-fluid seed)"),
             talus::model_entry<talus::eos::IdealGas>("eos", "ideal_gas", "ideal-gas EOS p = k rho (rock-fluid seed)"));
