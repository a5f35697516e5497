// The plugin's one exported symbol.
#include "driver/piper_driver.hpp"

ROBOTD_DRIVER_PLUGIN(robotd::piper::PiperDriver, "piper", "1.0.0")
