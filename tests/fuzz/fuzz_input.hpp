// Reads a fuzzer's input from the front: a few fixed fields that choose how the rest is used,
// then the rest. Reads past the end yield zeros and empty spans, so every input, even an empty
// one, is a valid case and the fuzzer never has to find a magic length first.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace robotd::fuzz {

class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : bytes_(data, size) {}

  std::uint8_t u8() {
    const auto field = take(1);
    return field.empty() ? std::uint8_t{0} : field[0];
  }

  std::uint32_t u32_le() {
    std::uint32_t value = 0;
    const auto field = take(4);
    for (std::size_t i = 0; i < field.size(); ++i) value |= static_cast<std::uint32_t>(field[i]) << (8 * i);
    return value;
  }

  std::int32_t i32_le() { return static_cast<std::int32_t>(u32_le()); }

  /// Up to `count` bytes.
  std::span<const std::uint8_t> take(std::size_t count) {
    const auto field = bytes_.first(std::min(count, bytes_.size()));
    bytes_ = bytes_.subspan(field.size());
    return field;
  }

  /// The text up to the next '\n' (which is consumed), or all that is left.
  std::string_view line() {
    const auto end = std::find(bytes_.begin(), bytes_.end(), std::uint8_t{'\n'});
    const auto length = static_cast<std::size_t>(end - bytes_.begin());
    const std::string_view text(reinterpret_cast<const char*>(bytes_.data()), length);
    bytes_ = bytes_.subspan(std::min(length + 1, bytes_.size()));
    return text;
  }

  std::span<const std::uint8_t> rest() { return take(bytes_.size()); }
  std::string_view rest_text() {
    const auto field = rest();
    return {reinterpret_cast<const char*>(field.data()), field.size()};
  }

 private:
  std::span<const std::uint8_t> bytes_;
};

/// Feeds `bytes` to `feed` in pieces of 1 … 256 bytes (`piece_seed` + 1), the way reads from a
/// socket or tty split a stream.
template <class Feed>
void feed_in_pieces(std::span<const std::uint8_t> bytes, std::uint8_t piece_seed, Feed&& feed) {
  const std::size_t piece = std::size_t{piece_seed} + 1;
  while (!bytes.empty()) {
    const auto chunk = bytes.first(std::min(piece, bytes.size()));
    feed(chunk);
    bytes = bytes.subspan(chunk.size());
  }
}

}  // namespace robotd::fuzz
