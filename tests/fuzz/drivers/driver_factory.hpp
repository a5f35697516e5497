// The drivers robotd ships, constructed by the name a config gives them ("driver": "piper"),
// for the fuzz targets that exercise a driver without its device. Each make_*_driver() lives in
// its own library because each driver's headers are found through its own include directory
// and two drivers' headers share names (driver/controller_link.hpp).
#pragma once

#include <array>
#include <memory>
#include <string_view>

#include "robotd/driver/driver.hpp"

namespace robotd::fuzz {

std::unique_ptr<driver::Driver> make_sim_driver();
std::unique_ptr<driver::Driver> make_piper_driver();
std::unique_ptr<driver::Driver> make_parol6_driver();
std::unique_ptr<driver::Driver> make_realman_driver();
std::unique_ptr<driver::Driver> make_xarm_driver();
std::unique_ptr<driver::Driver> make_hightorque_driver();

struct DriverEntry {
  std::string_view name;
  std::unique_ptr<driver::Driver> (*make)();
};

inline constexpr std::array<DriverEntry, 6> kDrivers{{
    {"sim", make_sim_driver},
    {"piper", make_piper_driver},
    {"parol6", make_parol6_driver},
    {"realman", make_realman_driver},
    {"xarm", make_xarm_driver},
    {"hightorque", make_hightorque_driver},
}};

/// The driver named `name`, not configured; nullptr for a name robotd does not ship.
inline std::unique_ptr<driver::Driver> make_driver(std::string_view name) {
  for (const DriverEntry& entry : kDrivers) {
    if (entry.name == name) return entry.make();
  }
  return nullptr;
}

}  // namespace robotd::fuzz
