// Stand-in for wjwwood's serial::Serial, the USB-CDC tty of the livelybot board: write() hands
// every packet to the harness, read() serves the bytes the harness queued and throws when they
// run out (which ends the SDK's receive loop, as a closed port does).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace serial {

struct Timeout {
  static Timeout simpleTimeout(std::uint32_t) { return {}; }
};

/// Every packet the SDK writes, and the bytes the emulated board sends back.
std::function<void(const std::vector<std::uint8_t>&)>& written();
std::deque<std::uint8_t>& incoming();

class Serial {
 public:
  void setPort(const std::string&) {}
  void setBaudrate(std::uint32_t) {}
  void setTimeout(const Timeout&) {}
  void open() {}
  bool isOpen() const { return true; }
  void close() {}
  void flush() {}
  std::size_t write(const std::uint8_t* data, std::size_t size) {
    if (written()) written()(std::vector<std::uint8_t>(data, data + size));
    return size;
  }
  std::size_t read(std::uint8_t* data, std::size_t size) {
    if (incoming().size() < size) {
      incoming().clear();
      throw std::runtime_error("no more bytes from the emulated board");
    }
    for (std::size_t i = 0; i < size; ++i) {
      data[i] = incoming().front();
      incoming().pop_front();
    }
    return size;
  }
};

}  // namespace serial
