#include "garbage_frames.hpp"

#include <array>

namespace robotd::piper::sim {
namespace {

// Feedback frames whose every byte carries a field: 0–5 bytes can never decode.
constexpr std::array<std::uint32_t, 20> kFullFeedbackIds = {0x2A1, 0x2A2, 0x2A3, 0x2A4, 0x2A5, 0x2A6, 0x2A7,
                                                            0x251, 0x252, 0x253, 0x254, 0x255, 0x256, 0x261,
                                                            0x262, 0x263, 0x264, 0x265, 0x266, 0x2A8};
constexpr int kShortestDecodable = 6;

std::uint8_t random_byte(std::mt19937& random) {
  return static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 255)(random));
}

}  // namespace

bool is_protocol_id(std::uint32_t id) {
  const auto in = [id](std::uint32_t first, std::uint32_t last) { return id >= first && id <= last; };
  return id == 0x121 || in(0x150, 0x15F) || in(0x181, 0x186) || id == 0x191 || in(0x251, 0x256) || in(0x261, 0x266) ||
         in(0x2A1, 0x2AC) || in(0x2B1, 0x2C8) || in(0x160, 0x17F) || id == 0x422 || in(0x470, 0x47E) ||
         in(0x481, 0x488) || id == 0x4AF;
}

CanMessage garbage_frame(std::mt19937& random) {
  CanMessage message;
  const int kind = std::uniform_int_distribution<int>(0, 2)(random);
  if (kind == 0) {  // a known feedback id, too short
    message.id =
        kFullFeedbackIds.at(std::uniform_int_distribution<std::size_t>(0, kFullFeedbackIds.size() - 1)(random));
    message.length = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, kShortestDecodable - 1)(random));
  } else if (kind == 1) {  // a standard id the protocol does not use
    do {
      message.id = std::uniform_int_distribution<std::uint32_t>(0, 0x7FF)(random);
    } while (is_protocol_id(message.id));
    message.length = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 8)(random));
  } else {  // an extended id: the PiPER uses standard ids only
    message.id = std::uniform_int_distribution<std::uint32_t>(0, 0x1FFFFFFF)(random);
    message.extended = true;
    message.length = static_cast<std::uint8_t>(std::uniform_int_distribution<int>(0, 8)(random));
  }
  for (std::size_t i = 0; i < message.length; ++i) message.data[i] = random_byte(random);
  return message;
}

}  // namespace robotd::piper::sim
