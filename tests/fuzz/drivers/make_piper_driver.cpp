#include "driver/piper_driver.hpp"
#include "driver_factory.hpp"

namespace robotd::fuzz {

std::unique_ptr<driver::Driver> make_piper_driver() { return std::make_unique<piper::PiperDriver>(); }

}  // namespace robotd::fuzz
