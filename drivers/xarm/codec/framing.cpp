// The command port's frames (§2.1, §2.2): the 6-byte header, and re-framing a TCP byte stream by
// its length field.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "xarm_codec.hpp"

namespace robotd::xarm {
namespace {

/// The largest length field that keeps a frame within kMaxFrameBytes.
constexpr std::size_t kMaxLengthField = kMaxFrameBytes - kHeaderBytes;

}  // namespace

Bytes encode_frame(const Frame& frame) {
  ByteWriter writer;
  writer.u16_be(frame.transaction_id)
      .u16_be(frame.protocol)
      .u16_be(static_cast<std::uint16_t>(1 + frame.body.size()))
      .u8(frame.reg)
      .bytes(frame.body);
  return writer.take();
}

void FrameSplitter::append(ByteView bytes) {
  if (broken_) return;  // nothing after a lost framing can be trusted until clear()
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

Result<std::optional<Frame>> FrameSplitter::next() {
  if (broken_) return make_error(ErrorCode::kInvalidArgument, *broken_);
  if (buffer_.size() < kHeaderBytes) return std::optional<Frame>{};
  ByteReader header(buffer_);
  Frame frame;
  frame.transaction_id = header.u16_be().value_or(0);
  frame.protocol = header.u16_be().value_or(0);
  const std::size_t length = header.u16_be().value_or(0);
  if (length == 0 || length > kMaxLengthField) {
    broken_ = "frame length field " + std::to_string(length) + " is outside 1.." + std::to_string(kMaxLengthField) +
              ": the command stream lost its framing (reconnect)";
    buffer_.clear();
    return make_error(ErrorCode::kInvalidArgument, *broken_);
  }
  const std::size_t frame_bytes = kHeaderBytes + length;
  if (buffer_.size() < frame_bytes) return std::optional<Frame>{};
  const auto frame_end = buffer_.begin() + static_cast<std::ptrdiff_t>(frame_bytes);
  const auto body_begin = buffer_.begin() + static_cast<std::ptrdiff_t>(kHeaderBytes + 1);
  frame.reg = buffer_[kHeaderBytes];
  frame.body.assign(body_begin, frame_end);
  buffer_.erase(buffer_.begin(), frame_end);
  return std::optional<Frame>(std::move(frame));
}

void FrameSplitter::clear() {
  buffer_.clear();
  broken_.reset();
}

}  // namespace robotd::xarm
