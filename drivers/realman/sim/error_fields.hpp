// The controller's errors as the configured --error-shape writes them (spec §4.1, §6.2).
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim_options.hpp"

namespace robotd::realman::sim {

/// Adds the error fields to `object`: "err": [codes] ([0] when healthy); "arm_err" and "sys_err"
/// (the first arm-side code, 0x1xxx/0x2xxx, and the first controller code, 0x5xxx; 0 for none);
/// or "err": the first code (0 for none).
void add_error_fields(nlohmann::json& object, ErrorShape shape, const std::vector<std::uint16_t>& errors);

/// The first code, 0 when healthy (gen 2's "arm_err" in a joint_state echo).
std::uint16_t first_error(const std::vector<std::uint16_t>& errors);

}  // namespace robotd::realman::sim
