// reset_zero as on the PI Plus: with the loop paused and no session, the motors go to zero
// torque, take their present angle as zero (written to flash), and zeroing succeeded when every
// one reads within 0.1 rad of it. The USB board zeroes a whole port at once, so there a port is
// zeroed whole or not at all. Every motor must acknowledge set-zero and save-to-flash (the board
// answers with the ids that did); the request goes out again every 20 ms until all did, as the
// board SDK's canport.cc does.
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "driver/hightorque_driver.hpp"
#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::hightorque {
namespace {

constexpr double kZeroTolerance_rad = 0.1;
constexpr auto kResendInterval = std::chrono::milliseconds(20);  // canport.cc's retry period

}  // namespace

Result<void> HighTorqueDriver::check_zeroable(std::span<const int> joints) const {
  for (const int joint : joints) {
    if (joint < 0 || static_cast<std::size_t>(joint) >= params_.motors.size()) {
      return make_error(ErrorCode::kInvalidArgument, "reset_zero: motor " + std::to_string(joint) +
                                                         " does not exist (0.." +
                                                         std::to_string(params_.motors.size() - 1) + ")");
    }
  }
  for (std::size_t b = 0; b < params_.buses.size(); ++b) {
    if (params_.buses[b].kind != BusParams::Kind::kBoard) continue;
    std::size_t named = 0;
    for (const int joint : joints) named += params_.motors[static_cast<std::size_t>(joint)].bus == b ? 1U : 0U;
    if (named != 0 && named != motors_on_bus_[b].size()) {
      return make_error(ErrorCode::kInvalidArgument,
                        "reset_zero: bus '" + params_.buses[b].name +
                            "' is a USB CAN board, which zeroes all its motors at once; name all " +
                            std::to_string(motors_on_bus_[b].size()) + " of them or none");
    }
  }
  return {};
}

Result<void> HighTorqueDriver::reset_zero(std::span<const int> joints) {
  abort_.clear();
  const Result<void> zeroed = zero(joints);
  if (zeroed || abort_.requested()) restart_silence_checks();
  return abort_.verdict(zeroed, "reset_zero");
}

Result<void> HighTorqueDriver::zero(std::span<const int> joints) {
  if (!connected_.load(std::memory_order_acquire)) {
    return make_error(ErrorCode::kNotAvailable, "reset_zero: the motors are not connected");
  }
  if (auto checked = check_zeroable(joints); !checked) return checked;
  const std::lock_guard lock(ops_mutex_);
  std::vector<std::size_t> motors;
  for (const int joint : joints) motors.push_back(static_cast<std::size_t>(joint));
  if (motors.empty()) {
    for (std::size_t m = 0; m < params_.motors.size(); ++m) motors.push_back(m);
  }

  // Zero torque, long enough for the robot to settle on its support, keeping the watchdog fed.
  const auto settled = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.zero_settle_ms);
  do {
    send_to_motors(motors, SystemRequest::Kind::kStop);
    if (!abort_.sleep_for(std::chrono::milliseconds(2))) return driver::aborted_error("settling before zeroing");
    drain_buses();
  } while (std::chrono::steady_clock::now() < settled);

  replies_.clear();
  if (auto done = acknowledged(motors, SystemRequest::Kind::kSetZero, "set zero"); !done) return done;
  if (params_.zero_save_to_flash) {
    if (auto done = acknowledged(motors, SystemRequest::Kind::kSaveToFlash, "save to flash"); !done) return done;
  }

  auto answered = await_motor_states(motors, std::chrono::milliseconds(params_.reply_timeout_ms), "after zeroing");
  if (!answered) return answered;
  std::string off;
  for (const std::size_t m : motors) {
    const MotorParams& motor = params_.motors[m];
    const double motor_rad = (motors_[m].status.position_rad - motor.zero_offset_rad) * motor.direction;
    if (std::fabs(motor_rad) > kZeroTolerance_rad) off += " " + motor.name + "=" + std::to_string(motor_rad);
  }
  if (!off.empty()) {
    return make_error(ErrorCode::kRefused, "reset_zero: motors not within 0.1 rad of their new zero:" + off);
  }
  return {};
}

void HighTorqueDriver::resend_to_pending(std::span<const std::size_t> motors, const std::vector<bool>& pending,
                                         SystemRequest::Kind kind) {
  // A board's admin packet covers its whole port: once per board bus is enough.
  std::vector<bool> board_sent(params_.buses.size(), false);
  std::vector<std::size_t> again;
  for (const std::size_t m : motors) {
    if (!pending[m]) continue;
    const std::size_t bus = params_.motors[m].bus;
    if (params_.buses[bus].kind == BusParams::Kind::kBoard) {
      if (board_sent[bus]) continue;
      board_sent[bus] = true;
    }
    again.push_back(m);
  }
  send_to_motors(again, kind);
}

Result<void> HighTorqueDriver::acknowledged(std::span<const std::size_t> motors, SystemRequest::Kind kind,
                                            const char* what) {
  std::vector<bool> pending(params_.motors.size(), false);
  std::size_t waiting = 0;
  for (const std::size_t m : motors) {
    pending[m] = true;
    ++waiting;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.reply_timeout_ms);
  auto next_send = std::chrono::steady_clock::now();
  while (waiting > 0 && std::chrono::steady_clock::now() < deadline) {
    if (std::chrono::steady_clock::now() >= next_send) {
      resend_to_pending(motors, pending, kind);
      next_send += kResendInterval;
    }
    if (!abort_.sleep_for(std::chrono::milliseconds(1))) {
      return driver::aborted_error(std::string("waiting for the answers to ") + what);
    }
    drain_buses();
    while (const auto reply = replies_.pop()) {
      if (reply->reply.kind != Reply::Kind::kResult) continue;
      for (const std::size_t m : motors) {
        if (!pending[m] || !from_motor(*reply, m)) continue;
        if (!reply->reply.result.success) {
          return make_error(ErrorCode::kRefused, "reset_zero: motor " + params_.motors[m].name + " refused " + what +
                                                     " (result " + std::to_string(reply->reply.result.code) + ")");
        }
        pending[m] = false;
        --waiting;
      }
    }
  }
  std::string missing;
  for (const std::size_t m : motors) {
    if (pending[m]) missing += " " + params_.motors[m].name;
  }
  if (!missing.empty()) {
    return make_error(ErrorCode::kTimeout, std::string("reset_zero: no answer to ") + what + " within " +
                                               std::to_string(params_.reply_timeout_ms) + " ms from" + missing);
  }
  return {};
}

}  // namespace robotd::hightorque
