#include "driver_factory.hpp"
#include "sim_driver.hpp"

namespace robotd::fuzz {

std::unique_ptr<driver::Driver> make_sim_driver() { return std::make_unique<sim::SimDriver>(); }

}  // namespace robotd::fuzz
