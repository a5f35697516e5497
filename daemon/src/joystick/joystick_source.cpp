#include "joystick/joystick_source.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include "rt/monotonic_clock.hpp"

namespace robotd::joystick {
namespace {

constexpr std::int64_t kRetryIntervalNs = rt::kNsPerSecond;
constexpr std::chrono::seconds kWarningInterval{10};
constexpr std::size_t kReadChunk = 64;  // records per read()
constexpr std::size_t kBitsPerLong = 8 * sizeof(unsigned long);

std::string errno_text(int error) { return std::strerror(error); }  // NOLINT(concurrency-mt-unsafe): one thread

std::string open_hint(int error) {
  if (error == ENOENT) return " (is the controller, or its USB receiver, plugged in?)";
  if (error == EACCES) return " (robotd's user needs read access: add it to the 'input' group)";
  return "";
}

// "'Logitech Gamepad F710', 8 axes, 11 buttons" from the device, or "" for a FIFO or a file.
std::string describe_device(int fd, Interface interface) {
  std::array<char, 128> name{};
  if (interface == Interface::kJs) {
    unsigned char axes = 0;
    unsigned char buttons = 0;
    if (ioctl(fd, JSIOCGNAME(name.size() - 1), name.data()) < 0)
      return "";                         // NOLINT(cppcoreguidelines-pro-type-vararg)
    ioctl(fd, JSIOCGAXES, &axes);        // NOLINT(cppcoreguidelines-pro-type-vararg)
    ioctl(fd, JSIOCGBUTTONS, &buttons);  // NOLINT(cppcoreguidelines-pro-type-vararg)
    return "'" + std::string(name.data()) + "', " + std::to_string(axes) + " axes, " + std::to_string(buttons) +
           " buttons";
  }
  if (ioctl(fd, EVIOCGNAME(name.size() - 1), name.data()) < 0) return "";  // NOLINT(cppcoreguidelines-pro-type-vararg)
  return "'" + std::string(name.data()) + "'";
}

}  // namespace

JoystickSource::JoystickSource(JoystickConfig config, Publish publish)
    : config_(std::move(config)),
      publish_(std::move(publish)),
      mapper_(config_),
      record_size_(config_.interface == Interface::kJs ? sizeof(js_event) : sizeof(input_event)),
      warnings_(kWarningInterval),
      wake_fd_(eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK)) {}

JoystickSource::~JoystickSource() {
  stop();
  if (wake_fd_ >= 0) close(wake_fd_);
}

void JoystickSource::start() {
  thread_ = driver::NamedThread("joystick", [this] { run(); });
}

void JoystickSource::stop() {
  if (!thread_.joinable()) return;
  stopping_.store(true);
  const std::uint64_t one = 1;
  (void)!write(wake_fd_, &one, sizeof(one));
  thread_.join();
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  mapper_.reset();
  publish_now();  // whoever teleoperates stops with robotd
}

void JoystickSource::run() {
  while (!stopping_.load()) {
    const std::int64_t now = rt::monotonic_now_ns();
    if (fd_ < 0 && !replay_finished_ && now >= next_open_ns_) try_open();
    if (fd_ >= 0 && replay_ && replay_due_ns_ <= now) {
      if (const std::string lost = read_device(); !lost.empty()) lose_device(lost);
    }
    if (fd_ >= 0 && config_.rate_hz > 0 && now >= next_publish_ns_) publish_now();

    std::array<pollfd, 2> fds{{{wake_fd_, POLLIN, 0}, {fd_, POLLIN, 0}}};
    // A replayed file is always readable: it is read when its next record is due, not on poll.
    const nfds_t count = fd_ >= 0 && !replay_ ? 2 : 1;
    const std::int64_t wait_ns = std::max<std::int64_t>(0, next_wake_ns() - rt::monotonic_now_ns());
    const int timeout_ms = static_cast<int>((wait_ns + rt::kNsPerMs - 1) / rt::kNsPerMs);
    if (poll(fds.data(), count, timeout_ms) <= 0) continue;
    if (count == 2 && fds[1].revents != 0) {
      if (const std::string lost = read_device(); !lost.empty()) lose_device(lost);
    }
  }
}

std::int64_t JoystickSource::next_wake_ns() const {
  std::int64_t next = rt::monotonic_now_ns() + kRetryIntervalNs;
  if (fd_ < 0) return replay_finished_ ? next : std::min(next, next_open_ns_);
  if (config_.rate_hz > 0) next = std::min(next, next_publish_ns_);
  if (replay_) next = std::min(next, replay_due_ns_);
  return next;
}

void JoystickSource::try_open() {
  const std::string& path = config_.device;
  next_open_ns_ = rt::monotonic_now_ns() + kRetryIntervalNs;
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);  // NOLINT(cppcoreguidelines-pro-type-vararg)
  if (fd < 0) {
    const int error = errno;
    warnings_.warn("open", "joystick: cannot open " + path + ": " + errno_text(error) + open_hint(error) +
                               "; retrying every second, /" + config_.topic + " stays neutral until then");
    publish_neutral_once();
    return;
  }
  struct stat info {};
  fstat(fd, &info);
  fd_ = fd;
  replay_ = S_ISREG(info.st_mode);
  replay_due_ns_ = 0;
  first_event_ns_ = -1;
  resyncing_ = false;
  buffer_.clear();
  mapper_.reset();
  const char* interface = config_.interface == Interface::kJs ? "js" : "evdev";
  std::string what = describe_device(fd, config_.interface);
  if (replay_) {
    what = std::string("replaying recorded ") + interface + " events";
  } else if (what.empty()) {
    what = std::string("not an input device: reading ") + interface + " events from it";
  }
  spdlog::info("joystick: {} ({}), publishing /{}", path, what, config_.topic);
  if (config_.interface == Interface::kEvdev) query_evdev_state();
  neutral_sent_ = false;
  publish_now();
}

void JoystickSource::query_evdev_state() {
  // What the device reports for its axes (range, current value) and buttons; a FIFO or a file
  // answers ENOTTY and the documented default ranges apply.
  for (const int code : mapper_.mapped_axes()) {
    input_absinfo absinfo{};
    const auto request = EVIOCGABS(static_cast<unsigned>(code));
    if (ioctl(fd_, request, &absinfo) < 0) continue;  // NOLINT(cppcoreguidelines-pro-type-vararg)
    mapper_.set_axis_range(code, absinfo.minimum, absinfo.maximum);
    mapper_.apply(
        input_event{.time = {}, .type = EV_ABS, .code = static_cast<std::uint16_t>(code), .value = absinfo.value});
  }
  std::array<unsigned long, KEY_MAX / kBitsPerLong + 1> keys{};
  if (ioctl(fd_, EVIOCGKEY(sizeof(keys)), keys.data()) < 0) return;  // NOLINT(cppcoreguidelines-pro-type-vararg)
  for (const int code : mapper_.mapped_buttons()) {
    const auto index = static_cast<std::size_t>(code);
    const bool pressed = ((keys.at(index / kBitsPerLong) >> (index % kBitsPerLong)) & 1UL) != 0;
    mapper_.apply(
        input_event{.time = {}, .type = EV_KEY, .code = static_cast<std::uint16_t>(code), .value = pressed ? 1 : 0});
  }
}

std::string JoystickSource::read_device() {
  std::array<unsigned char, kReadChunk * sizeof(input_event)> chunk{};
  bool changed = false;
  std::string lost;
  while (lost.empty()) {
    // A replay reads only when no whole record is waiting, so that it keeps its pace.
    if (!(replay_ && buffer_.size() >= record_size_)) {
      const ssize_t got = read(fd_, chunk.data(), kReadChunk * record_size_);
      const int error = errno;
      if (got == 0) {
        lost = replay_ ? "end of file" : "end of file: its writer closed it";
        break;
      }
      if (got < 0) {
        if (error != EAGAIN && error != EINTR) lost = "read: " + errno_text(error);  // ENODEV: unplugged
        break;
      }
      buffer_.insert(buffer_.end(), chunk.begin(), chunk.begin() + got);
    }
    changed = apply_buffered(rt::monotonic_now_ns()) || changed;
    if (replay_) break;  // come back when the next record is due
  }
  if (changed) publish_now();
  return lost;
}

bool JoystickSource::apply_buffered(std::int64_t now_ns) {
  std::size_t offset = 0;
  bool changed = false;
  replay_due_ns_ = 0;
  while (buffer_.size() - offset >= record_size_) {
    const unsigned char* record = buffer_.data() + offset;
    if (replay_) {
      std::int64_t event_ns = 0;
      if (config_.interface == Interface::kJs) {
        js_event event{};
        std::memcpy(&event, record, sizeof(event));
        event_ns = static_cast<std::int64_t>(event.time) * rt::kNsPerMs;
      } else {
        input_event event{};
        std::memcpy(&event, record, sizeof(event));
        event_ns = static_cast<std::int64_t>(event.input_event_sec) * rt::kNsPerSecond +
                   static_cast<std::int64_t>(event.input_event_usec) * 1000;
      }
      if (first_event_ns_ < 0) {
        first_event_ns_ = event_ns;
        replay_origin_ns_ = now_ns;
      }
      const std::int64_t due = replay_origin_ns_ + std::max<std::int64_t>(0, event_ns - first_event_ns_);
      if (due > now_ns) {
        replay_due_ns_ = due;
        break;
      }
    }
    changed = apply_record(record) || changed;
    offset += record_size_;
  }
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(offset));
  return changed;
}

bool JoystickSource::apply_record(const unsigned char* record) {
  if (config_.interface == Interface::kJs) {
    js_event event{};
    std::memcpy(&event, record, sizeof(event));
    return mapper_.apply(event);
  }
  input_event event{};
  std::memcpy(&event, record, sizeof(event));
  if (event.type == EV_SYN && event.code == SYN_DROPPED) {
    resyncing_ = true;  // the kernel's buffer overflowed: drop up to the next report, then ask the device
    return false;
  }
  if (resyncing_) {
    if (event.type == EV_SYN && event.code == SYN_REPORT) {
      resyncing_ = false;
      const Joy before = mapper_.joy();
      query_evdev_state();
      return !same_values(before, mapper_.joy());
    }
    return false;
  }
  return mapper_.apply(event);
}

void JoystickSource::lose_device(const std::string& why) {
  close(fd_);
  fd_ = -1;
  mapper_.reset();
  if (replay_) {
    replay_finished_ = true;
    spdlog::info("joystick: end of the recorded events in {}; /{} is neutral", config_.device, config_.topic);
    publish_now();
    return;
  }
  warnings_.warn("lost", "joystick: lost " + config_.device + " (" + why + "); /" + config_.topic +
                             " is neutral, reopening every second");
  next_open_ns_ = rt::monotonic_now_ns() + kRetryIntervalNs;
  publish_neutral_once();
}

void JoystickSource::publish_neutral_once() {
  if (neutral_sent_) return;
  neutral_sent_ = true;
  mapper_.reset();
  publish_now();
}

void JoystickSource::publish_now() {
  Joy joy = mapper_.joy();
  joy.header.stamp = Time::from_ns(rt::realtime_now_ns());
  joy.header.frame_id = config_.device;
  publish_(joy);
  if (config_.rate_hz > 0) next_publish_ns_ = rt::monotonic_now_ns() + rt::kNsPerSecond / config_.rate_hz;
}

}  // namespace robotd::joystick
