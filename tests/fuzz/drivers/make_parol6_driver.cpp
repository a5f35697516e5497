#include "driver/parol6_driver.hpp"
#include "driver_factory.hpp"

namespace robotd::fuzz {

std::unique_ptr<driver::Driver> make_parol6_driver() { return std::make_unique<parol6::Parol6Driver>(); }

}  // namespace robotd::fuzz
