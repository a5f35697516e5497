// Each driver's "params" parser (parse_*_params, through configure() as robotd calls it) on any
// JSON a config can hold. configure() must accept or refuse with a message, never crash or throw;
// and the device it accepts must describe joints robotd can run: 1 … kMaxJoints of them, every
// limit finite, position_min_rad below position_max_rad, no negative maximum or gain.
//
// Input: the driver's name ("sim", "piper", …) on the first line, then the params JSON.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include <nlohmann/json.hpp>

#include "drivers/driver_factory.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input.hpp"

namespace {

using robotd::driver::JointDescription;

bool finite_and_not_negative(double value) { return std::isfinite(value) && value >= 0; }

void check_joint(const JointDescription& joint) {
  const robotd::driver::JointLimits& limits = joint.limits;
  FUZZ_CHECK(std::isfinite(limits.position_min_rad) && std::isfinite(limits.position_max_rad));
  FUZZ_CHECK(limits.position_min_rad < limits.position_max_rad);
  FUZZ_CHECK(finite_and_not_negative(limits.velocity_max_rad_s));
  FUZZ_CHECK(finite_and_not_negative(limits.acceleration_max_rad_s2));
  FUZZ_CHECK(finite_and_not_negative(limits.effort_max_nm));
  FUZZ_CHECK(finite_and_not_negative(limits.kp_max) && finite_and_not_negative(limits.kd_max));
  FUZZ_CHECK(finite_and_not_negative(joint.default_kp) && finite_and_not_negative(joint.default_kd));
  FUZZ_CHECK(std::isfinite(joint.zero_position_rad));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  robotd::fuzz::FuzzInput input(data, size);
  auto driver = robotd::fuzz::make_driver(input.line());
  if (!driver) return 0;
  const std::string_view text = input.rest_text();
  const nlohmann::json params = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  if (params.is_discarded()) return 0;

  const auto configured = driver->configure(params);
  if (!configured) {
    FUZZ_CHECK(!configured.error().message.empty());
    return 0;
  }
  const robotd::driver::DeviceDescription description = driver->describe();
  FUZZ_CHECK(!description.joints.empty() && description.joints.size() <= robotd::driver::kMaxJoints);
  FUZZ_CHECK(std::isfinite(description.native_rate_hz) && description.native_rate_hz > 0);
  for (const JointDescription& joint : description.joints) check_joint(joint);
  return 0;
}
