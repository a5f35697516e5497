// Request → reply exchanges with the arm for the ops: queries (0x472, 0x477, 0x4AF) and
// settings acknowledged on 0x476. The RT thread reads the bus and hands replies over through
// the reply ring; an exchange waits on that ring.
#include <thread>

#include "driver/hex_text.hpp"
#include "driver/piper_driver.hpp"
#include "robotd/driver/monotonic_clock.hpp"

namespace robotd::piper {
namespace {

using namespace std::chrono_literals;

}  // namespace

Result<std::vector<CanMessage>> PiperDriver::exchange(std::span<const CanMessage> requests, std::uint32_t reply_id,
                                                      std::size_t count) {
  if (!snapshot().link_up) {
    return make_error(ErrorCode::kNotAvailable,
                      "the arm is not connected (robotctl status shows why; robotctl call <device> recover)");
  }
  replies_.clear();
  for (const CanMessage& request : requests) {
    if (send(request) != transport::CanIo::kDone) {
      return make_error(ErrorCode::kTransport,
                        "could not send " + can_id_text(request.id) + " on " + link_name_.data());
    }
  }
  std::vector<CanMessage> replies;
  replies.reserve(count);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.reply_timeout_ms);
  while (replies.size() < count) {
    if (const auto message = replies_.pop()) {
      if (message->id == reply_id && !(reply_id == can_id::kFirmware && is_firmware_request(*message))) {
        replies.push_back(*message);
      }
      continue;
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      return make_error(ErrorCode::kTimeout, "no answer (" + can_id_text(reply_id) + ") from the arm within " +
                                                 std::to_string(params_.reply_timeout_ms) + " ms; got " +
                                                 std::to_string(replies.size()) + " of " + std::to_string(count) +
                                                 " (firmware too old for this query, or the arm is busy?)");
    }
    std::this_thread::sleep_for(1ms);
  }
  return replies;
}

Result<SetAck> PiperDriver::set_and_await_ack(const CanMessage& request, std::uint8_t command, bool maintenance) {
  if (!snapshot().link_up) {
    return make_error(ErrorCode::kNotAvailable,
                      "the arm is not connected (robotctl status shows why; robotctl call <device> recover)");
  }
  replies_.clear();
  if (send(request) != transport::CanIo::kDone) {
    return make_error(ErrorCode::kTransport, "could not send " + can_id_text(request.id) + " on " + link_name_.data());
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(params_.reply_timeout_ms);
  while (std::chrono::steady_clock::now() < deadline) {
    if (maintenance) drain_link_blocking_free(driver::monotonic_now_ns());
    const auto message = replies_.pop();
    if (!message) {
      if (!maintenance) {
        std::this_thread::sleep_for(1ms);
      } else if (!abort_.sleep_for(1ms)) {
        return driver::aborted_error("waiting for the acknowledge of " + can_id_text(request.id));
      }
      continue;
    }
    const auto frame = decode(*message, codec_);
    const auto* ack = frame ? std::get_if<SetAck>(&*frame) : nullptr;
    if (ack != nullptr && ack->command == command) return *ack;
  }
  return make_error(ErrorCode::kTimeout, "the arm did not acknowledge " + can_id_text(request.id) + " (no 0x476 with " +
                                             can_id_text(command) + ") within " +
                                             std::to_string(params_.reply_timeout_ms) + " ms");
}

}  // namespace robotd::piper
