#include "device/command_mailbox.hpp"

namespace robotd::device {

void CommandMailbox::post(std::uint8_t slot, std::uint32_t generation, const control::ValidatedCommand& command,
                          std::int64_t received_ns, std::int64_t sent_ns, std::uint64_t answers_tick) noexcept {
  const std::uint64_t sequence = ++sequence_;
  for (std::size_t i = 0; i < command.count; ++i) {
    const control::JointTargetUpdate& update = command.joints[i];
    JointTarget& target = working_.joints[update.joint];
    target.generation = generation;
    target.sequence = sequence;
    target.received_ns = received_ns;
    target.sent_ns = sent_ns;
    target.update = update;
  }
  working_.slots[slot] = SlotActivity{generation, received_ns, answers_tick};
  channel_.commands.write_buffer() = working_;
  channel_.commands.publish();
}

}  // namespace robotd::device
