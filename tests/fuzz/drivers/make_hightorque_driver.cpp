#include "driver/hightorque_driver.hpp"
#include "driver_factory.hpp"

namespace robotd::fuzz {

std::unique_ptr<driver::Driver> make_hightorque_driver() { return std::make_unique<hightorque::HighTorqueDriver>(); }

}  // namespace robotd::fuzz
