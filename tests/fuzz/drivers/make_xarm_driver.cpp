#include "driver/xarm_driver.hpp"
#include "driver_factory.hpp"

namespace robotd::fuzz {

std::unique_ptr<driver::Driver> make_xarm_driver() { return std::make_unique<xarm::XarmDriver>(); }

}  // namespace robotd::fuzz
