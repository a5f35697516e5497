// A serial line a driver uses from its RT thread (termios, raw 8N1, no flow control,
// non-blocking), and the pseudo-terminal a simulator offers in place of the device.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>

#include "robotd/driver/json_reader.hpp"
#include "robotd/result.hpp"

namespace robotd::transport {

struct SerialConfig {
  std::string device = "/dev/ttyACM0";
  int baud = 3'000'000;  // one of the termios rates (B9600 … B4000000)
};

/// Reads a "serial" params object: {"device": "/dev/ttyACM0", "baud": 3000000}.
SerialConfig read_serial_link(JsonReader& reader);

enum class SerialIo : std::uint8_t {
  kDone,    // read: `count` > 0 bytes in `out`; write: `count` bytes handed to the kernel
  kNone,    // read: nothing waiting; write: the kernel buffer is full (nothing written)
  kClosed,  // the device is gone (USB unplugged, simulator exited) or was never opened
};

class SerialPort {
 public:
  explicit SerialPort(SerialConfig config) : config_(std::move(config)) {}
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;
  ~SerialPort() { close(); }

  /// Opens and configures the line; the error says what is wrong and what to do (a missing
  /// device: is it plugged in; permission: the dialout group; not a terminal; an unsupported baud).
  Result<void> open();
  void close() noexcept;
  bool is_open() const { return fd_ >= 0; }
  /// The open line's descriptor (−1 when closed), for a reader thread to poll(); read through read().
  int fd() const { return fd_; }

  /// Non-blocking, RT-safe: one system call, no allocation.
  SerialIo read(std::span<std::uint8_t> out, std::size_t& count) noexcept;
  SerialIo write(std::span<const std::uint8_t> bytes, std::size_t& count) noexcept;
  /// Drops what is waiting in both directions (after a reconnect).
  void flush() noexcept;

  std::string describe() const { return "serial " + config_.device; }

 private:
  SerialConfig config_;
  int fd_ = -1;
};

/// The simulator's side: a pseudo-terminal pair in raw mode. A driver opens device_path() (or
/// the symlink made at `link_path`) like a real serial port; the simulator reads and writes fd().
/// Reading fd() fails with EIO while no process holds the device end open: no host connected.
/// close() hangs up the device end (a host reading it sees the line closed).
class PseudoTerminal {
 public:
  PseudoTerminal() = default;
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;
  ~PseudoTerminal() { close(); }

  /// Creates the pair; with a non-empty `link_path`, also a symlink there to the device end
  /// (replacing a stale one). Non-blocking.
  Result<void> open(const std::string& link_path);
  void close() noexcept;
  int fd() const { return master_; }
  const std::string& device_path() const { return device_path_; }

 private:
  int master_ = -1;
  std::string device_path_;
  std::string link_path_;
};

}  // namespace robotd::transport
