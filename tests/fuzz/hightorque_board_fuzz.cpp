// The livelybot USB-CDC board codec (drivers/hightorque/codec) on any byte stream the board's tty
// can deliver: the 0xF7 packet splitter (CRC-8 header, CRC-16 payload), then every packet's
// payload read as state records (what the driver decodes) and as command slots (what the
// simulator decodes). Every packet must re-frame to itself; states and slots must survive
// encode → decode up to one wire count (truncation toward zero, as the SDK converts), once the
// first round has applied the encoder's saturation.
//
// Input: u8 read size − 1, u8 highest motor id with a scaling (board torque scaling), then the
// stream.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/hightorque_codec.hpp"
#include "fuzz_check.hpp"
#include "fuzz_input.hpp"

namespace {

using namespace robotd::hightorque;
using robotd::fuzz::FuzzInput;

constexpr MotorScaling kBoardScaling{.torque_per_unit = 0.004938, .torque_offset_nm = 0.0, .gain_factor = 1.0};
constexpr std::size_t kMaxRecords = kMaxBoardPayload / kBoardShortStateRecordSize;

/// Equal, both NaN, or apart by at most one wire count of any field at this scaling.
bool same_value(double a, double b) {
  if (a == b || (std::isnan(a) && std::isnan(b))) return true;
  return std::abs(a - b) <= 0.1 + 1e-6 * std::abs(a);
}

void check_reframes(const BoardFrame& frame) {
  std::array<std::uint8_t, kBoardHeaderSize + kMaxBoardPayload> packet{};
  const std::size_t size = encode_board_frame(frame.command, frame.bytes(), packet);
  FUZZ_CHECK(size == kBoardHeaderSize + frame.length);
  BoardFrameSplitter splitter;
  FUZZ_CHECK(splitter.feed(std::span(packet).first(size)) == size);
  BoardFrame again;
  FUZZ_CHECK(splitter.next(again));
  FUZZ_CHECK(again.command == frame.command && again.length == frame.length);
  FUZZ_CHECK(std::equal(frame.bytes().begin(), frame.bytes().end(), again.bytes().begin()));
  FUZZ_CHECK(splitter.crc_errors() == 0 && splitter.skipped_bytes() == 0);
}

/// encode → decode of `states`, which must keep every record.
std::vector<BoardMotorState> states_round(BoardCommand command, std::span<const BoardMotorState> states,
                                          std::span<const MotorScaling> scaling) {
  std::array<std::uint8_t, kMaxBoardPayload> payload{};
  const std::size_t size = encode_board_states(command, states, scaling, payload);
  FUZZ_CHECK(size != 0);
  std::vector<BoardMotorState> decoded(states.size());
  FUZZ_CHECK(decode_board_states(command, std::span(payload).first(size), scaling, decoded) == states.size());
  return decoded;
}

void read_states(const BoardFrame& frame, std::span<const MotorScaling> scaling) {
  std::array<BoardMotorState, kMaxRecords> states{};
  const std::size_t count = decode_board_states(frame.command, frame.bytes(), scaling, states);
  if (count == 0) return;
  const auto first = states_round(frame.command, std::span(states).first(count), scaling);
  const auto second = states_round(frame.command, first, scaling);
  for (std::size_t i = 0; i < count; ++i) {
    FUZZ_CHECK(second[i].motor == first[i].motor && second[i].mode == first[i].mode);
    FUZZ_CHECK(second[i].fault == first[i].fault);
    FUZZ_CHECK(same_value(second[i].position_rad, first[i].position_rad));
    FUZZ_CHECK(same_value(second[i].velocity_rad_s, first[i].velocity_rad_s));
    FUZZ_CHECK(same_value(second[i].torque_nm, first[i].torque_nm));
  }
}

/// encode → decode of the slots `requests` carry (motors 1 … n in order, as decoded).
std::vector<MotorRequest> slots_round(BoardCommand command, std::span<const MotorRequest> requests,
                                      std::span<const MotorScaling> scaling) {
  std::vector<BlockSlot> slots;
  for (const MotorRequest& request : requests)
    slots.push_back(BlockSlot{.motor = request.motor, .command = request.command});
  int highest = 0;
  for (const MotorRequest& request : requests) highest = std::max(highest, request.motor);
  BoardSlotBuffer buffer(highest);
  const std::span<const std::uint8_t> payload = buffer.update(command, slots, scaling);
  FUZZ_CHECK(!payload.empty());
  std::vector<MotorRequest> decoded(requests.size());
  FUZZ_CHECK(decode_board_slots(command, payload, scaling, decoded) == requests.size());
  return decoded;
}

void read_slots(const BoardFrame& frame, std::span<const MotorScaling> scaling) {
  std::array<MotorRequest, kMaxRecords> requests{};
  const std::size_t count = decode_board_slots(frame.command, frame.bytes(), scaling, requests);
  if (count == 0) return;
  const auto first = slots_round(frame.command, std::span(requests).first(count), scaling);
  const auto second = slots_round(frame.command, first, scaling);
  for (std::size_t i = 0; i < count; ++i) {
    const MotorCommand& a = first[i].command;
    const MotorCommand& b = second[i].command;
    FUZZ_CHECK(second[i].motor == first[i].motor && second[i].has_position == first[i].has_position);
    FUZZ_CHECK(a.mode == b.mode && same_value(a.position_rad, b.position_rad));
    FUZZ_CHECK(same_value(a.velocity_rad_s, b.velocity_rad_s) && same_value(a.torque_nm, b.torque_nm));
    FUZZ_CHECK(same_value(a.kp, b.kp) && same_value(a.kd, b.kd));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzInput input(data, size);
  const std::uint8_t piece = input.u8();
  // A port has motors 1…30 at most.
  const std::size_t highest = std::min<std::size_t>(input.u8(), kMaxMotorId);
  const std::vector<MotorScaling> scaling(highest + 1, kBoardScaling);  // [0] unused

  BoardFrameSplitter splitter;
  std::size_t fed = 0;
  std::size_t framed = 0;
  robotd::fuzz::feed_in_pieces(input.rest(), piece, [&](std::span<const std::uint8_t> bytes) {
    while (!bytes.empty()) {
      const std::size_t used = splitter.feed(bytes);
      bytes = bytes.subspan(used);
      fed += used;
      BoardFrame frame;
      bool took = false;
      while (splitter.next(frame)) {
        took = true;
        FUZZ_CHECK(frame.length <= kMaxBoardPayload);
        framed += kBoardHeaderSize + frame.length;
        check_reframes(frame);
        read_states(frame, scaling);
        read_slots(frame, scaling);
      }
      FUZZ_CHECK(used != 0 || took || bytes.empty());  // never stalls
    }
  });
  // Every byte is in a packet, skipped, or still buffered.
  FUZZ_CHECK(framed + splitter.skipped_bytes() <= fed);
  return 0;
}
