#include "firmware_info.hpp"

#include <algorithm>

namespace robotd::piper::sim {
namespace {

constexpr std::size_t kChunk = 8;
constexpr std::size_t kTextLength = kFirmwareFrames * kChunk;

void put(std::string& text, std::size_t at, const std::string& field, std::size_t width) {
  std::string padded = field.substr(0, width);
  padded.resize(width, ' ');
  text.replace(at, width, padded);
}

}  // namespace

std::string firmware_text(const std::string& software_version) {
  std::string text(kTextLength, ' ');
  put(text, 0, kHardwareVersion, 8);
  put(text, 16, "01", 2);      // motor ratio / batch
  put(text, 32, "ARM_MC", 6);  // node type: the main controller
  put(text, 60, software_version, 8);
  put(text, 68, "240501", 6);  // production date
  put(text, 76, "01", 2);      // node number
  return text;
}

std::vector<CanMessage> firmware_reply(const std::string& software_version, const CodecOptions& options) {
  const std::string text = firmware_text(software_version);
  std::vector<CanMessage> frames;
  frames.reserve(kFirmwareFrames);
  for (std::size_t at = 0; at < text.size(); at += kChunk) {
    FirmwareChunk chunk;
    std::copy_n(text.begin() + static_cast<std::ptrdiff_t>(at), kChunk, chunk.text.begin());
    chunk.length = static_cast<std::uint8_t>(kChunk);
    frames.push_back(encode(chunk, options));
  }
  return frames;
}

}  // namespace robotd::piper::sim
