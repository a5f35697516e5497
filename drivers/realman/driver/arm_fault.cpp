#include "driver/arm_fault.hpp"

#include <string>

namespace robotd::realman {

driver::FaultInfo arm_fault(std::span<const std::uint16_t> errors, std::span<const std::uint16_t> joint_errors) {
  driver::FaultInfo fault;
  std::string text;
  for (const std::uint16_t code : errors) {
    if (fault.code == 0) fault.code = code;
    text += (text.empty() ? "" : "; ") + system_error_text(code);
  }
  for (std::size_t j = 0; j < joint_errors.size(); ++j) {
    constexpr std::uint16_t kFrameLoss = 0xF000;  // a value of its own, not a set of bits
    const auto bits =
        joint_errors[j] == kFrameLoss ? kFrameLoss : static_cast<std::uint16_t>(joint_errors[j] & ~kJointWarningBits);
    if (bits == 0) continue;
    if (fault.code == 0) fault.code = kJointFaultBase + static_cast<std::int32_t>((j + 1) * 0x10000 + bits);
    text += (text.empty() ? "" : "; ") + ("joint " + std::to_string(j + 1) + ": " + joint_error_text(bits));
  }
  if (fault.code != 0) fault.set(fault.code, ("controller reports " + text).c_str());
  return fault;
}

}  // namespace robotd::realman
