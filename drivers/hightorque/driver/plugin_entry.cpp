#include "driver/hightorque_driver.hpp"

ROBOTD_DRIVER_PLUGIN(robotd::hightorque::HighTorqueDriver, "hightorque", "1.0.0");
