// The plugin's one exported symbol.
#include "driver/parol6_driver.hpp"

ROBOTD_DRIVER_PLUGIN(robotd::parol6::Parol6Driver, "parol6", "1.0.0")
