// The joystick source: a thread of its own (never the RT thread) that reads a game controller
// through the Linux joystick (js) or event (evdev) interface, keeps its state with a
// JoystickMapper and hands robotd_msgs/Joy samples to `publish`: on every change and at
// rate_hz while the device is there.
//
// The device may be missing or go away (unplugged, receiver out of range): the source then logs
// a warning naming the path (at most every 10 s), publishes one neutral (all zero) sample so
// teleop clients stop, and tries to open it again every second. The path may also be a FIFO
// (a test or a tool writing recorded events; its writer closing counts as an unplug) or a
// regular file of recorded events, which is replayed once at its recorded pace and then
// followed by a neutral sample.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "app/throttled_log.hpp"
#include "joystick/joystick_config.hpp"
#include "joystick/joystick_mapper.hpp"
#include "robotd/driver/named_thread.hpp"

namespace robotd::joystick {

class JoystickSource {
 public:
  using Publish = std::function<void(const Joy&)>;

  JoystickSource(JoystickConfig config, Publish publish);
  JoystickSource(const JoystickSource&) = delete;
  JoystickSource& operator=(const JoystickSource&) = delete;
  ~JoystickSource();

  void start();
  /// Ends the thread, then publishes a last neutral sample.
  void stop();

 private:
  void run();
  void try_open();
  void query_evdev_state();
  /// Reads what the device has and publishes a change; why the device is gone, or "" while it is there.
  std::string read_device();
  /// Applies the complete records buffered so far (a replay only those that are due).
  bool apply_buffered(std::int64_t now_ns);
  bool apply_record(const unsigned char* record);
  void lose_device(const std::string& why);
  void publish_now();
  void publish_neutral_once();
  std::int64_t next_wake_ns() const;

  JoystickConfig config_;
  Publish publish_;
  JoystickMapper mapper_;
  std::size_t record_size_;
  app::ThrottledLog warnings_;

  int fd_ = -1;
  int wake_fd_ = -1;  // eventfd: stop() wakes the thread's poll
  bool replay_ = false;
  bool replay_finished_ = false;
  bool resyncing_ = false;     // evdev SYN_DROPPED: events until the next SYN_REPORT are stale
  bool neutral_sent_ = false;  // since the device was last lost
  std::int64_t replay_origin_ns_ = 0;
  std::int64_t first_event_ns_ = -1;
  std::int64_t replay_due_ns_ = 0;  // a replay's next record is due then (0: none waiting)
  std::int64_t next_open_ns_ = 0;
  std::int64_t next_publish_ns_ = 0;
  std::vector<unsigned char> buffer_;
  std::atomic<bool> stopping_{false};
  driver::NamedThread thread_;
};

}  // namespace robotd::joystick
