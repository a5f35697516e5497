#include "driver/xarm_driver.hpp"

ROBOTD_DRIVER_PLUGIN(robotd::xarm::XarmDriver, "xarm", "1.0.0")
