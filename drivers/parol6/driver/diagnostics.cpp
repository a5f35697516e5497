// Parol6Driver::diagnostics(): what DeviceStatus shows of the board (robotctl status).
#include <cstdio>

#include "driver/parol6_driver.hpp"

namespace robotd::parol6 {
namespace {

std::string homed_text(const RobotFrame& reply) {
  if (reply.all_homed()) return "all joints";
  std::string joints;
  for (int j = 0; j < kJoints; ++j) {
    if (reply.joint_homed(j)) joints += (joints.empty() ? "J" : ", J") + std::to_string(j + 1);
  }
  return (joints.empty() ? std::string("none") : joints) + " (robotctl call <device> home)";
}

}  // namespace

driver::Diagnostics Parol6Driver::diagnostics() const {
  const BoardSnapshot snapshot = snapshot_.load_non_rt();
  const RobotFrame& reply = snapshot.reply;
  std::array<char, 96> frames{};
  std::snprintf(frames.data(), frames.size(), "%llu sent, %llu replies, %llu rejected, %llu bytes skipped",
                static_cast<unsigned long long>(snapshot.frames_sent),
                static_cast<unsigned long long>(snapshot.replies), static_cast<unsigned long long>(snapshot.rejected),
                static_cast<unsigned long long>(snapshot.discarded));
  driver::Diagnostics values{
      {"link", std::string(link_name_.data()) + (snapshot.link_up ? " (up)" : " (down)")},
      {"frames", frames.data()},
  };
  if (!snapshot.have_reply) return values;
  std::array<char, 64> timing{};
  // The board's own measure of the time between the host's last two frames.
  std::snprintf(timing.data(), timing.size(), "%.2f ms between frames (%u ticks)",
                reply.timing_ticks * kTimingTickSeconds * 1e3, static_cast<unsigned>(reply.timing_ticks));
  std::array<char, 64> io_text{};
  std::snprintf(io_text.data(), io_text.size(), "IN1 %d IN2 %d OUT1 %d OUT2 %d", (reply.io & io::kIn1) != 0,
                (reply.io & io::kIn2) != 0, (reply.io & io::kOut1) != 0, (reply.io & io::kOut2) != 0);
  values.emplace_back("homed", homed_text(reply));
  values.emplace_back("estop_input", reply.estop_pressed() ? "PRESSED" : "released");
  values.emplace_back("io", io_text.data());
  values.emplace_back("board_timing", timing.data());
  // Bits 0–1 are always set; any joint bit set is an error this firmware does not report yet.
  if ((reply.temperature_error & 0xFCU) != 0 || (reply.position_error & 0xFCU) != 0) {
    std::array<char, 64> errors{};
    std::snprintf(errors.data(), errors.size(), "temperature 0x%02X, position 0x%02X", reply.temperature_error,
                  reply.position_error);
    values.emplace_back("joint_errors", errors.data());
  }
  std::array<char, 64> gripper{};
  std::snprintf(gripper.data(), gripper.size(), "position %d, current %d mA, status 0x%02X",
                static_cast<int>(reply.gripper_position), static_cast<int>(reply.gripper_current),
                reply.gripper_status);
  values.emplace_back("gripper", gripper.data());
  if (trajectory_.running()) values.emplace_back("moving", "a device_call move is running");
  return values;
}

}  // namespace robotd::parol6
