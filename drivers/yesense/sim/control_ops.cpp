// The control channel's ops (README.md in this folder): what tests ask the emulator to report,
// where to put the body, and what to do wrong.
#include <cmath>
#include <numbers>
#include <string>

#include <spdlog/spdlog.h>

#include "imu_simulator.hpp"
#include "robotd/sim_control/control_request.hpp"
#include "robotd/sim_control/sim_clock.hpp"

namespace robotd::imu::sim {
namespace {

using nlohmann::json;
using sim_control::expect_fields;
using sim_control::integer_field;
using sim_control::RequestError;

constexpr std::int64_t kMaxDurationMs = 3'600'000;
constexpr std::int64_t kMaxByteCount = 1'000'000;
constexpr std::int64_t kMaxFrameCount = 1'000'000;
constexpr const char* kOps = "state, set_orientation, sway, garbage, corrupt, pause, disconnect";

/// A required angle field within ±`limit` rad.
double angle_field(const json& request, const std::string& op, const char* name, double limit) {
  const double value = sim_control::number_field(request, op, name);
  if (!(std::abs(value) <= limit)) {
    throw RequestError("op \"" + op + "\": \"" + name + "\" must be within ±" + std::to_string(limit) + " rad, not " +
                       std::to_string(value));
  }
  return value;
}

json euler_json(const EulerRad& euler) {
  return {{"roll_rad", euler.roll}, {"pitch_rad", euler.pitch}, {"yaw_rad", euler.yaw}};
}

}  // namespace

json ImuSimulator::control(const json& request) {
  try {
    const std::string op = sim_control::op_of(request, kOps);
    const std::int64_t now = sim_control::monotonic_ns();
    if (op == "state") {
      expect_fields(request, op, {});
      return state(now);
    }
    if (op == "set_orientation") {
      expect_fields(request, op, {"roll_rad", "pitch_rad", "yaw_rad"});
      const EulerRad base{.roll = angle_field(request, op, "roll_rad", std::numbers::pi),
                          .pitch = angle_field(request, op, "pitch_rad", std::numbers::pi / 2),
                          .yaw = angle_field(request, op, "yaw_rad", std::numbers::pi)};
      body_.hold(base);
      spdlog::info("holding still at roll {:.4f}, pitch {:.4f}, yaw {:.4f} rad", base.roll, base.pitch, base.yaw);
    } else if (op == "sway") {
      expect_fields(request, op, {});
      body_.hold(body_.orientation(now));
      body_.sway(now);
    } else if (op == "garbage") {
      expect_fields(request, op, {"count"});
      garbage_pending_ += static_cast<std::uint64_t>(integer_field(request, op, "count", 1, kMaxByteCount));
    } else if (op == "corrupt") {
      expect_fields(request, op, {"count"});
      corrupt_pending_ += static_cast<std::uint64_t>(integer_field(request, op, "count", 1, kMaxFrameCount));
    } else if (op == "pause") {
      expect_fields(request, op, {"for_ms"});
      paused_until_ns_ = now + integer_field(request, op, "for_ms", 0, kMaxDurationMs) * 1'000'000;
    } else if (op == "disconnect") {
      expect_fields(request, op, {"for_ms"});
      const std::int64_t for_ms = integer_field(request, op, "for_ms", 0, kMaxDurationMs);
      close_line();
      reopen_line_at_ns_ = now + for_ms * 1'000'000;
    } else {
      throw RequestError("unknown op \"" + op + "\"; ops: " + kOps);
    }
    return {{"ok", true}};
  } catch (const RequestError& error) {
    return sim_control::error_reply(error.what());
  }
}

json ImuSimulator::state(std::int64_t now_ns) const {
  return {{"ok", true},
          {"rate_hz", options_.rate_hz},
          {"line_open", line_open_},
          {"host_connected", host_connected_},
          {"paused", now_ns < paused_until_ns_},
          {"swaying", body_.swaying()},
          {"orientation", euler_json(body_.orientation(now_ns))},
          {"sequence", sequence_},
          {"frames_sent", frames_sent_},
          {"frames_dropped", frames_dropped_},
          {"frames_corrupted", frames_corrupted_},
          {"corrupt_pending", corrupt_pending_},
          {"garbage_sent", garbage_sent_},
          {"garbage_pending", garbage_pending_},
          {"bytes_received", bytes_received_}};
}

}  // namespace robotd::imu::sim
