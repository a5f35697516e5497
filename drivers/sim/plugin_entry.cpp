// The plugin's one exported symbol.
#include "sim_driver.hpp"

ROBOTD_DRIVER_PLUGIN(robotd::sim::SimDriver, "sim", "1.0.0")
