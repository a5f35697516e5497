#include "line_faults.hpp"

#include <algorithm>

namespace robotd::parol6::sim {

std::size_t LineFaults::filter(std::span<std::uint8_t> bytes) {
  std::size_t kept = 0;
  for (const std::uint8_t byte : bytes) {
    if (drop_pending_ > 0) {
      --drop_pending_;
      ++dropped_;
      continue;
    }
    std::uint8_t out = byte;
    if (garble_pending_ > 0) {
      --garble_pending_;
      ++garbled_;
      out = static_cast<std::uint8_t>(out ^ kGarbleMask);
    }
    bytes[kept++] = out;
  }
  return kept;
}

std::size_t LineFaults::take_garbage(std::span<std::uint8_t> out) {
  const auto count =
      static_cast<std::size_t>(std::min<std::int64_t>(garbage_pending_, static_cast<std::int64_t>(out.size())));
  std::uniform_int_distribution<int> byte(0, 255);
  for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<std::uint8_t>(byte(random_));
  garbage_pending_ -= static_cast<std::int64_t>(count);
  garbage_sent_ += count;
  return count;
}

}  // namespace robotd::parol6::sim
