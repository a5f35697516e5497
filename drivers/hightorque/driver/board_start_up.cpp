#include "driver/board_start_up.hpp"

#include <algorithm>
#include <functional>
#include <optional>
#include <string>

#include "driver/version_text.hpp"

namespace robotd::hightorque {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// How often the SDK repeats each step (canport.cc: 20 ms; robot.cc: 100 ms for versions).
constexpr milliseconds kRepeatEvery{20};
constexpr milliseconds kVersionsEvery{100};
constexpr int kFdcanResets = 3;
constexpr int kFdcanResetFrom = 41;    // board firmware 4.1, in tenths
constexpr int kVersionQueryFrom = 40;  // board firmware 4.0 answers 0x0B and 0x06
constexpr int kAnswerFrom = 20;        // the SDK waits for a board version of at least 2.0

/// One port's packets during start-up: sends, and hands every packet received to a callback.
class StartUpLink {
 public:
  StartUpLink(transport::SerialPort& port, milliseconds timeout, const driver::AbortFlag& abort)
      : port_(port), timeout_(timeout), abort_(abort) {}

  Result<void> send(BoardCommand command, int payload_byte) {
    std::array<std::uint8_t, kBoardHeaderSize + 1> packet{};
    const std::size_t size = encode_board_admin(command, payload_byte, packet);
    std::size_t written = 0;
    if (port_.write(std::span(packet).first(size), written) == transport::SerialIo::kClosed) {
      return make_error(ErrorCode::kNotAvailable, port_.describe() + " closed during the board start-up");
    }
    return {};
  }

  /// Sends `command` every `every` until `answered` accepts a packet; false after the timeout.
  Result<bool> ask(BoardCommand command, int payload_byte, milliseconds every,
                   const std::function<bool(const BoardFrame&)>& answered) {
    const auto deadline = Clock::now() + timeout_;
    auto next_send = Clock::now();
    while (Clock::now() < deadline) {
      if (Clock::now() >= next_send) {
        if (auto sent = send(command, payload_byte); !sent) return sent.error();
        next_send += every;
      }
      if (!abort_.sleep_for(milliseconds(1))) {
        return driver::aborted_error("waiting for board " + port_.describe() + " to answer its start-up");
      }
      auto read = drain(answered);
      if (!read) return read.error();
      if (read.value()) return true;
    }
    return false;
  }

 private:
  Result<bool> drain(const std::function<bool(const BoardFrame&)>& answered) {
    std::array<std::uint8_t, 4096> bytes{};
    bool done = false;
    while (true) {
      std::size_t count = 0;
      const transport::SerialIo io = port_.read(bytes, count);
      if (io == transport::SerialIo::kClosed) {
        return make_error(ErrorCode::kNotAvailable, port_.describe() + " closed during the board start-up");
      }
      if (io == transport::SerialIo::kNone) return done;
      std::span<const std::uint8_t> rest(bytes.data(), count);
      while (!rest.empty()) {
        rest = rest.subspan(splitter_.feed(rest));
        while (splitter_.next(frame_)) done = answered(frame_) || done;
      }
    }
  }

  transport::SerialPort& port_;
  milliseconds timeout_;
  const driver::AbortFlag& abort_;
  BoardFrameSplitter splitter_;
  BoardFrame frame_;
};

Error no_answer(const transport::SerialPort& port, const std::string& step, milliseconds timeout) {
  return make_error(ErrorCode::kTimeout, "board " + port.describe() + ": no answer to " + step + " within " +
                                             std::to_string(timeout.count()) +
                                             " ms: is it a livelybot CAN board, powered, and the right tty?");
}

Result<BoardFirmware> read_board_firmware(StartUpLink& link, const transport::SerialPort& port, int motor_count,
                                          milliseconds timeout) {
  std::optional<BoardFirmware> firmware;
  auto asked = link.ask(BoardCommand::kSetMotorCount, motor_count, kRepeatEvery, [&](const BoardFrame& frame) {
    if (frame.command != BoardCommand::kSetMotorCount) return false;
    firmware = decode_board_firmware(frame.bytes());
    return firmware && firmware->tenths() >= kAnswerFrom;
  });
  if (!asked) return asked.error();
  if (!asked.value()) return no_answer(port, "0x05 (set the port's motor count, read the board firmware)", timeout);
  if (firmware->tenths() < kVersionQueryFrom) {
    return make_error(ErrorCode::kNotAvailable,
                      "board " + port.describe() + " has firmware " + std::to_string(firmware->major) + "." +
                          std::to_string(firmware->minor) +
                          ": robotd needs 4.0 or later (motor firmware query 0x0B and state requests); update it");
  }
  return *firmware;
}

Result<void> read_motor_firmware(StartUpLink& link, const transport::SerialPort& port, std::span<const int> motor_ids,
                                 milliseconds timeout, BoardSetup& setup) {
  const auto all_known = [&] {
    return std::ranges::all_of(
        motor_ids, [&](int id) { return setup.motor_firmware.at(static_cast<std::size_t>(id)).major != 0; });
  };
  auto asked = link.ask(BoardCommand::kVersion, kBroadcastId, kVersionsEvery, [&](const BoardFrame& frame) {
    if (frame.command != BoardCommand::kVersion) return false;
    std::array<FirmwareVersion, kMaxMotorId> versions{};
    const std::size_t count = decode_board_versions(frame.bytes(), versions);
    for (std::size_t i = 0; i < count; ++i) {
      if (versions[i].motor <= kMaxMotorId)
        setup.motor_firmware.at(static_cast<std::size_t>(versions[i].motor)) = versions[i];
    }
    return all_known();
  });
  if (!asked) return asked.error();
  if (asked.value()) return {};
  std::string missing;
  for (const int id : motor_ids) {
    if (setup.motor_firmware.at(static_cast<std::size_t>(id)).major == 0) {
      missing += (missing.empty() ? "" : ", ") + std::to_string(id);
    }
  }
  return make_error(ErrorCode::kTimeout, "board " + port.describe() + ": motor(s) " + missing +
                                             " did not report their firmware (0x0B) within " +
                                             std::to_string(timeout.count()) +
                                             " ms: are they powered, wired to this port, and are the ids right?");
}

/// The function version the lowest motor firmware allows; refuses what robotd cannot drive.
Result<BoardFunction> function_for(const transport::SerialPort& port, std::span<const int> motor_ids,
                                   const BoardSetup& setup) {
  FirmwareVersion lowest = setup.motor_firmware.at(static_cast<std::size_t>(motor_ids.front()));
  bool any_five = false;
  bool all_five = true;
  for (const int id : motor_ids) {
    const FirmwareVersion& version = setup.motor_firmware.at(static_cast<std::size_t>(id));
    if (version.older_than(lowest)) lowest = version;
    any_five = any_five || version.major == 5;
    all_five = all_five && version.major == 5;
  }
  if (any_five && !all_five) {
    return make_error(ErrorCode::kInvalidArgument, "board " + port.describe() +
                                                       ": firmware-5 motors share the port with others; the "
                                                       "vendor SDK refuses that mix too");
  }
  const BoardFunction function = board_function_for(lowest);
  if (function < BoardFunction::kV2) {
    return make_error(ErrorCode::kNotAvailable,
                      "board " + port.describe() + ": motor " + std::to_string(lowest.motor) + " has firmware " +
                          version_text(lowest) +
                          "; robotd needs 4.2.0 or later (the board answers state requests from it)");
  }
  return function;
}

}  // namespace

Result<BoardSetup> start_up_board(transport::SerialPort& port, std::span<const int> motor_ids,
                                  std::chrono::milliseconds timeout, const driver::AbortFlag& abort) {
  if (motor_ids.empty()) return make_error(ErrorCode::kInvalidArgument, "board " + port.describe() + ": no motors");
  StartUpLink link(port, timeout, abort);
  BoardSetup setup;
  auto firmware = read_board_firmware(link, port, static_cast<int>(motor_ids.size()), timeout);
  if (!firmware) return firmware.error();
  setup.firmware = firmware.value();
  if (setup.firmware.tenths() >= kFdcanResetFrom) {
    for (int i = 0; i < kFdcanResets; ++i) {
      if (auto sent = link.send(BoardCommand::kFdcanReset, 0); !sent) return sent.error();
    }
  }
  if (auto read = read_motor_firmware(link, port, motor_ids, timeout, setup); !read) return read.error();
  auto function = function_for(port, motor_ids, setup);
  if (!function) return function.error();
  setup.function = function.value();
  const auto code = static_cast<std::uint8_t>(setup.function);
  auto echoed = link.ask(BoardCommand::kSetFunctionVersion, code, kRepeatEvery, [&](const BoardFrame& frame) {
    return frame.command == BoardCommand::kSetFunctionVersion && frame.length >= 1 && frame.payload[0] == code;
  });
  if (!echoed) return echoed.error();
  if (!echoed.value()) return no_answer(port, "0x0C (set the board's function version)", timeout);
  return setup;
}

}  // namespace robotd::hightorque
