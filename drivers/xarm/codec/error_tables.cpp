// Words for the controller's error and warning codes (§6.1, §6.2) and the joint servos' error
// codes (§6.3).
#include <algorithm>
#include <array>
#include <string>
#include <string_view>

#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

struct CodeText {
  int code;
  std::string_view text;
};

constexpr auto kControllerErrors = std::to_array<CodeText>({
    {1, "emergency-stop button on the control box pressed"},
    {2, "control-box emergency-stop IO triggered"},
    {3, "three-state enabling switch e-stop pressed"},
    {10, "servo motor error"},
    {11, "servo motor 1 error"},
    {12, "servo motor 2 error"},
    {13, "servo motor 3 error"},
    {14, "servo motor 4 error"},
    {15, "servo motor 5 error"},
    {16, "servo motor 6 error"},
    {17, "servo motor 7 error"},
    {18, "force-torque sensor communication error"},
    {19, "end-effector communication error"},
    {21, "kinematics error"},
    {22, "self-collision"},
    {23, "joint angle exceeds limit"},
    {24, "speed exceeds limit"},
    {25, "planning error"},
    {26, "Linux RT error"},
    {27, "command reply error"},
    {28, "end module communication error"},
    {29, "other errors"},
    {30, "feedback speed exceeds limit"},
    {31, "collision caused abnormal current"},
    {32, "three-point circle calculation error"},
    {33, "controller GPIO error"},
    {34, "recording timeout"},
    {35, "safety boundary limit"},
    {36, "too many delay commands"},
    {37, "abnormal motion in manual mode"},
    {38, "abnormal joint angle"},
    {39, "power-board master/slave IC communication error"},
    {40, "no IK solution / error-free joint trajectory solve failed"},
    {41, "friction file invalid"},
    {42, "calibration file invalid"},
    {50, "F/T sensor read error"},
    {51, "F/T sensor set-mode error"},
    {52, "F/T sensor set-zero error"},
    {53, "F/T sensor overloaded / reading over limit"},
    {60, "linear speed exceeded limit in servo_j mode"},
    {110, "arm base board communication error"},
    {111, "control-box external RS485 device communication error"},
});

constexpr auto kControllerWarnings = std::to_array<CodeText>({
    {11, "command cache full"},
    {12, "command parameter error"},
    {13, "command (register) does not exist"},
    {14, "command has no solution"},
    {15, "Modbus command queue full"},
});

constexpr auto kServoErrors = std::to_array<CodeText>({
    {10, "current detection error"},
    {11, "joint over-current"},
    {12, "joint over-speed"},
    {14, "position command over limit"},
    {15, "joint over-temperature"},
    {16, "encoder init error"},
    {17, "single-turn encoder error"},
    {18, "multi-turn encoder error"},
    {19, "low battery voltage"},
    {20, "driver IC hardware error"},
    {21, "driver IC init error"},
    {22, "encoder config error"},
    {23, "large position deviation"},
    {26, "joint positive over-run"},
    {27, "joint negative over-run"},
    {28, "joint command error (not enabled)"},
    {33, "drive overload"},
    {34, "motor overload"},
    {35, "motor type error"},
    {36, "driver type error"},
    {39, "joint over-voltage"},
    {40, "joint under-voltage"},
    {49, "EEPROM read/write error"},
    {52, "motor angle init error"},
    {58, "torque command timeout"},
});

constexpr int kLastEstopError = 3;

template <std::size_t N>
std::string_view lookup(const std::array<CodeText, N>& table, int code) {
  const auto found =
      std::find_if(table.begin(), table.end(), [code](const CodeText& entry) { return entry.code == code; });
  return found == table.end() ? std::string_view{} : found->text;
}

/// "C23 joint angle exceeds limit": `prefix` and the code, then the table's words or `unknown`.
template <std::size_t N>
std::string coded_text(const std::array<CodeText, N>& table, std::string_view prefix, int code,
                       std::string_view unknown) {
  if (code == 0) return "";
  const std::string_view text = lookup(table, code);
  return std::string(prefix) + std::to_string(code) + " " + std::string(text.empty() ? unknown : text);
}

}  // namespace

std::string controller_error_text(int code) {
  return coded_text(kControllerErrors, "C", code, "unknown controller error");
}

std::string controller_warning_text(int code) { return coded_text(kControllerWarnings, "W", code, "unknown warning"); }

std::string servo_error_text(int code) {
  if (code == 0) return "";
  const std::string_view text = lookup(kServoErrors, code);
  return text.empty() ? "servo error " + std::to_string(code) : std::string(text);
}

bool is_estop_error(int code) { return code >= 1 && code <= kLastEstopError; }

}  // namespace robotd::xarm
