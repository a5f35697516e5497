#include "robotd/transport/serial_port.hpp"

#include <array>
#include <cerrno>
#include <cstdlib>
#include <fcntl.h>
#include <optional>
#include <sys/file.h>
#include <sys/stat.h>
#include <system_error>
#include <termios.h>
#include <unistd.h>

#include "errno_text.hpp"

namespace robotd::transport {
namespace {

struct BaudRate {
  int baud;
  speed_t code;
};

constexpr std::array<BaudRate, 18> kBaudRates = {{
    {9600, B9600},
    {19200, B19200},
    {38400, B38400},
    {57600, B57600},
    {115200, B115200},
    {230400, B230400},
    {460800, B460800},
    {500000, B500000},
    {576000, B576000},
    {921600, B921600},
    {1000000, B1000000},
    {1152000, B1152000},
    {1500000, B1500000},
    {2000000, B2000000},
    {2500000, B2500000},
    {3000000, B3000000},
    {3500000, B3500000},
    {4000000, B4000000},
}};

std::optional<speed_t> baud_code(int baud) {
  for (const BaudRate& rate : kBaudRates) {
    if (rate.baud == baud) return rate.code;
  }
  return std::nullopt;
}

std::string supported_bauds() {
  std::string text;
  for (const BaudRate& rate : kBaudRates) {
    if (!text.empty()) text += ", ";
    text += std::to_string(rate.baud);
  }
  return text;
}

/// Raw 8N1, no flow control, modem lines ignored, no translation or echo. VMIN 1 / VTIME 0
/// rather than 0 / 0: with O_NONBLOCK a read never waits either way, but with VMIN 0 an empty
/// line reads as 0 bytes, the same as a hang-up; with VMIN 1 it is EAGAIN and 0 means the
/// device is gone (USB unplugged, the simulator's pty closed).
void make_raw(termios& settings) {
  cfmakeraw(&settings);
  settings.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
  settings.c_cflag |= static_cast<tcflag_t>(CS8 | CREAD | CLOCAL);
  settings.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  settings.c_cc[VMIN] = 1;
  settings.c_cc[VTIME] = 0;
}

Error open_error(const std::string& device, int error) {
  switch (error) {
    case ENOENT:
      return make_error(
          ErrorCode::kNotAvailable,
          "serial device " + device + " does not exist: is the arm's USB cable plugged in? (ls /dev/ttyACM*)");
    case EACCES:
    case EPERM:
      return make_error(ErrorCode::kNotAvailable,
                        "no permission to open serial device " + device +
                            ": add the user running robotd to the dialout group (sudo usermod -aG dialout USER, then "
                            "log in again) or install a udev rule for the device");
    case EBUSY:
      return make_error(ErrorCode::kNotAvailable, "serial device " + device +
                                                      " is in use by another program (another robotd, a terminal "
                                                      "program, ModemManager?): close it first");
    case ENXIO:
    case ENODEV:
      return make_error(ErrorCode::kNotAvailable,
                        "serial device " + device + " has no device behind it (" + errno_text(error) + "): unplugged?");
    default:
      return make_error(ErrorCode::kNotAvailable,
                        "cannot open serial device " + device + " (" + errno_text(error) + ")");
  }
}

}  // namespace

SerialConfig read_serial_link(JsonReader& reader) {
  SerialConfig config;
  reader.require("device", "the serial device, e.g. \"/dev/ttyACM0\" (or a simulator's pty link)");
  config.device = reader.string_or("device", config.device);
  if (reader.has("device") && config.device.empty()) reader.error("device", "must not be empty");
  const auto baud = reader.integer("baud", 1, 100'000'000);
  if (baud) {
    if (baud_code(static_cast<int>(*baud))) {
      config.baud = static_cast<int>(*baud);
    } else {
      reader.error("baud", "expected one of " + supported_bauds() + ", got " + std::to_string(*baud));
    }
  }
  reader.finish();
  return config;
}

Result<void> SerialPort::open() {
  close();
  if (config_.device.empty()) return make_error(ErrorCode::kInvalidArgument, "no serial device given");
  const auto speed = baud_code(config_.baud);
  if (!speed) {
    return make_error(ErrorCode::kInvalidArgument, "serial baud rate " + std::to_string(config_.baud) +
                                                       " is not supported; use one of " + supported_bauds() +
                                                       " (the PAROL6 uses 3000000)");
  }
  const int fd = ::open(config_.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return open_error(config_.device, errno);
  const auto fail = [&](ErrorCode code, std::string message) {
    ::close(fd);
    return make_error(code, std::move(message));
  };
  termios settings{};
  if (tcgetattr(fd, &settings) != 0) {
    const int error = errno;
    if (error == ENOTTY || error == EINVAL) {
      return fail(ErrorCode::kInvalidArgument, config_.device +
                                                   " is not a terminal, so not a serial device: point \"device\" at "
                                                   "the arm's /dev/ttyACMn (or a simulator's pty link)");
    }
    return fail(ErrorCode::kNotAvailable,
                "cannot read the settings of " + config_.device + " (" + errno_text(error) + ")");
  }
  // One user at a time: a second robotd (or another driver instance) on the same line would
  // steal half of the replies. An advisory lock rather than TIOCEXCL: the lock goes with the
  // process (even when it is killed), while TIOCEXCL stays on a pty's device end after close.
  if (flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
    return fail(ErrorCode::kNotAvailable,
                "serial device " + config_.device + " is in use: another process (another robotd?) has it open");
  }
  make_raw(settings);
  if (cfsetispeed(&settings, *speed) != 0 || cfsetospeed(&settings, *speed) != 0 ||
      tcsetattr(fd, TCSANOW, &settings) != 0) {
    return fail(ErrorCode::kNotAvailable, "cannot set " + config_.device + " to raw 8N1 at " +
                                              std::to_string(config_.baud) + " baud (" + errno_text(errno) + ")");
  }
  fd_ = fd;
  return {};
}

void SerialPort::close() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

SerialIo SerialPort::read(std::span<std::uint8_t> out, std::size_t& count) noexcept {
  count = 0;
  if (fd_ < 0) return SerialIo::kClosed;
  if (out.empty()) return SerialIo::kNone;
  while (true) {
    const ssize_t n = ::read(fd_, out.data(), out.size());
    if (n > 0) {
      count = static_cast<std::size_t>(n);
      return SerialIo::kDone;
    }
    if (n == 0) return SerialIo::kClosed;  // VMIN 1: no data would be EAGAIN, so this is a hang-up
    if (errno == EINTR) continue;
    return errno == EAGAIN || errno == EWOULDBLOCK ? SerialIo::kNone : SerialIo::kClosed;
  }
}

SerialIo SerialPort::write(std::span<const std::uint8_t> bytes, std::size_t& count) noexcept {
  count = 0;
  if (fd_ < 0) return SerialIo::kClosed;
  if (bytes.empty()) return SerialIo::kDone;
  while (true) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n >= 0) {
      count = static_cast<std::size_t>(n);
      return n > 0 ? SerialIo::kDone : SerialIo::kNone;
    }
    if (errno == EINTR) continue;
    return errno == EAGAIN || errno == EWOULDBLOCK ? SerialIo::kNone : SerialIo::kClosed;
  }
}

void SerialPort::flush() noexcept {
  if (fd_ >= 0) tcflush(fd_, TCIOFLUSH);
}

// --- the simulator's side ------------------------------------------------------------------------

Result<void> PseudoTerminal::open(const std::string& link_path) {
  close();
  const int master = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (master < 0) {
    return make_error(ErrorCode::kNotAvailable,
                      "cannot create a pseudo-terminal (" + errno_text(errno) + "): is /dev/pts mounted?");
  }
  const auto fail = [&](const std::string& message) {
    const int error = errno;
    ::close(master);
    return make_error(ErrorCode::kNotAvailable, message + " (" + errno_text(error) + ")");
  };
  std::array<char, 128> name{};
  if (grantpt(master) != 0 || unlockpt(master) != 0 || ptsname_r(master, name.data(), name.size()) != 0) {
    return fail("cannot unlock the pseudo-terminal");
  }
  // Termios calls on the master act on the device end: raw, as a USB CDC port is.
  termios settings{};
  if (tcgetattr(master, &settings) != 0) return fail("cannot read the pseudo-terminal's settings");
  make_raw(settings);
  cfsetispeed(&settings, B3000000);
  cfsetospeed(&settings, B3000000);
  if (tcsetattr(master, TCSANOW, &settings) != 0) return fail("cannot make the pseudo-terminal raw");
  const int flags = fcntl(master, F_GETFL);
  if (flags < 0 || fcntl(master, F_SETFL, flags | O_NONBLOCK) != 0) {
    return fail("cannot make the pseudo-terminal non-blocking");
  }
  const std::string device = name.data();
  // Until the device end has been opened once, reading the master says EAGAIN (as if a silent
  // host were there); after a close it says EIO. Open and close it now, so EIO means "no host"
  // from the start.
  const int slave = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave < 0) return fail("cannot open the pseudo-terminal's device end " + device);
  ::close(slave);
  if (!link_path.empty()) {
    struct stat existing {};
    if (lstat(link_path.c_str(), &existing) == 0 && !S_ISLNK(existing.st_mode)) {
      ::close(master);
      return make_error(ErrorCode::kNotAvailable, link_path + " exists and is not a symlink: not replacing it");
    }
    // Made under a temporary name and renamed over the old link: a host never sees it missing.
    const std::string temporary = link_path + ".new-" + std::to_string(getpid());
    unlink(temporary.c_str());
    if (symlink(device.c_str(), temporary.c_str()) != 0) return fail("cannot create the symlink " + link_path);
    if (rename(temporary.c_str(), link_path.c_str()) != 0) {
      const auto error = fail("cannot create the symlink " + link_path);
      unlink(temporary.c_str());
      return error;
    }
  }
  master_ = master;
  device_path_ = device;
  link_path_ = link_path;
  return {};
}

void PseudoTerminal::close() noexcept {
  if (master_ < 0) return;
  ::close(master_);  // the device end hangs up: a host reading it sees the line closed
  master_ = -1;
  if (!link_path_.empty()) {
    // Only our own link: another simulator may have taken the path over since.
    std::array<char, 128> target{};
    const ssize_t length = readlink(link_path_.c_str(), target.data(), target.size() - 1);
    if (length > 0 && device_path_ == std::string_view(target.data(), static_cast<std::size_t>(length))) {
      unlink(link_path_.c_str());
    }
  }
  device_path_.clear();
  link_path_.clear();
}

}  // namespace robotd::transport
