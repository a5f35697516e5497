#include "driver/realman_driver.hpp"
#include "driver_factory.hpp"

namespace robotd::fuzz {

std::unique_ptr<driver::Driver> make_realman_driver() { return std::make_unique<realman::RealmanDriver>(); }

}  // namespace robotd::fuzz
