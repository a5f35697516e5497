// The plugin's one exported symbol.
#include "driver/realman_driver.hpp"

ROBOTD_DRIVER_PLUGIN(robotd::realman::RealmanDriver, "realman", "1.0.0")
