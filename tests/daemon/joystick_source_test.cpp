// The joystick source's thread against real file descriptors, no DDS: a FIFO stands for the
// device (its writer closing is an unplug), a regular file for a recording.
#include "joystick/joystick_source.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <fcntl.h>
#include <fstream>
#include <functional>
#include <mutex>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include <gtest/gtest.h>

namespace robotd::joystick {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

constexpr std::int16_t kAxisFull = 32767;

js_event js(std::uint32_t time_ms, std::uint8_t type, std::uint8_t number, std::int16_t value) {
  return js_event{.time = time_ms, .value = value, .type = type, .number = number};
}

// What the source published, with when it arrived.
class Published {
 public:
  void add(const Joy& joy) {
    const std::lock_guard lock(mutex_);
    samples_.push_back({joy, Clock::now()});
    changed_.notify_all();
  }
  /// The first sample from index `from` on that satisfies `predicate`, waiting up to `timeout`.
  std::optional<std::size_t> wait_for(const std::function<bool(const Joy&)>& predicate, std::size_t from,
                                      std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    std::optional<std::size_t> found;
    changed_.wait_for(lock, timeout, [&] {
      for (std::size_t i = from; i < samples_.size(); ++i) {
        if (predicate(samples_[i].joy)) {
          found = i;
          return true;
        }
      }
      return false;
    });
    return found;
  }
  std::size_t size() {
    const std::lock_guard lock(mutex_);
    return samples_.size();
  }
  Clock::time_point at(std::size_t index) {
    const std::lock_guard lock(mutex_);
    return samples_.at(index).at;
  }
  Joy joy(std::size_t index) {
    const std::lock_guard lock(mutex_);
    return samples_.at(index).joy;
  }

 private:
  struct Sample {
    Joy joy;
    Clock::time_point at;
  };
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<Sample> samples_;
};

bool neutral(const Joy& joy) { return same_values(joy, Joy{}); }

class JoystickSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::array<char, 64> dir{};
    std::snprintf(dir.data(), dir.size(), "/tmp/robotd-joystick-XXXXXX");
    ASSERT_NE(mkdtemp(dir.data()), nullptr);
    dir_ = dir.data();
    path_ = dir_ + "/js0";
  }
  void TearDown() override {
    source_.reset();
    std::remove(path_.c_str());
    rmdir(dir_.c_str());
  }

  void start(int rate_hz = 0) {
    JoystickConfig config;
    config.device = path_;
    config.rate_hz = rate_hz;
    config.deadzone = 0;
    config.mapping = default_mapping(Interface::kJs);
    source_ = std::make_unique<JoystickSource>(config, [this](const Joy& joy) { published_.add(joy); });
    source_->start();
  }

  static void write_events(int fd, const std::vector<js_event>& events) {
    for (const js_event& event : events)
      ASSERT_EQ(write(fd, &event, sizeof(event)), static_cast<ssize_t>(sizeof(event)));
  }

  std::string dir_;
  std::string path_;
  Published published_;
  std::unique_ptr<JoystickSource> source_;
};

TEST_F(JoystickSourceTest, MissingDeviceGivesOneNeutralSampleNotOnePerRetry) {
  start(50);
  ASSERT_TRUE(published_.wait_for(neutral, 0, 2s));
  std::this_thread::sleep_for(2500ms);  // two retries
  EXPECT_EQ(published_.size(), 1U);
}

TEST_F(JoystickSourceTest, EventsFromTheDeviceArePublishedOnChange) {
  ASSERT_EQ(mkfifo(path_.c_str(), 0600), 0);
  start();
  const int fd = open(path_.c_str(), O_WRONLY);  // blocks until the source has opened it
  ASSERT_GE(fd, 0);
  write_events(fd, {js(0, JS_EVENT_BUTTON | JS_EVENT_INIT, 0, 0), js(0, JS_EVENT_AXIS | JS_EVENT_INIT, 1, 0),
                    js(10, JS_EVENT_AXIS, 1, -kAxisFull), js(20, JS_EVENT_BUTTON, 0, 1)});
  EXPECT_TRUE(published_.wait_for([](const Joy& joy) { return joy.l_vertical == 1.0F && joy.a == 1.0F; }, 0, 2s));
  close(fd);
}

TEST_F(JoystickSourceTest, UnpluggedDeviceGivesANeutralSampleAndIsReopened) {
  ASSERT_EQ(mkfifo(path_.c_str(), 0600), 0);
  start();
  int fd = open(path_.c_str(), O_WRONLY);
  ASSERT_GE(fd, 0);
  write_events(fd, {js(0, JS_EVENT_AXIS, 0, -kAxisFull)});
  const auto pushed = published_.wait_for([](const Joy& joy) { return joy.l_horizontal == 1.0F; }, 0, 2s);
  ASSERT_TRUE(pushed);
  close(fd);  // the writer goes: an unplug
  const auto lost = published_.wait_for(neutral, *pushed + 1, 2s);
  ASSERT_TRUE(lost) << "no neutral sample after the device went away";

  fd = open(path_.c_str(), O_WRONLY);  // blocks until the source has reopened it
  ASSERT_GE(fd, 0);
  write_events(fd, {js(0, JS_EVENT_BUTTON, 3, 1)});
  EXPECT_TRUE(published_.wait_for([](const Joy& joy) { return joy.y == 1.0F; }, *lost + 1, 3s));
  close(fd);
}

TEST_F(JoystickSourceTest, PublishesAtRateHzWhileTheDeviceIsThere) {
  ASSERT_EQ(mkfifo(path_.c_str(), 0600), 0);
  start(50);
  const int fd = open(path_.c_str(), O_WRONLY);
  ASSERT_GE(fd, 0);
  const std::size_t before = published_.size();
  std::this_thread::sleep_for(1s);
  const std::size_t count = published_.size() - before;
  EXPECT_GE(count, 35U);
  EXPECT_LE(count, 60U);
  close(fd);
}

TEST_F(JoystickSourceTest, RecordedFileIsReplayedAtItsPaceThenNeutral) {
  {
    std::ofstream file(path_, std::ios::binary);
    for (const js_event& event : {js(5000, JS_EVENT_BUTTON, 1, 1), js(5400, JS_EVENT_BUTTON, 2, 1)}) {
      file.write(reinterpret_cast<const char*>(&event),
                 sizeof(event));  // NOLINT(cppcoreguidelines-pro-type-reinterpret-cast)
    }
  }
  start();
  const auto first = published_.wait_for([](const Joy& joy) { return joy.b == 1.0F; }, 0, 2s);
  ASSERT_TRUE(first);
  const auto second = published_.wait_for([](const Joy& joy) { return joy.x == 1.0F; }, *first, 2s);
  ASSERT_TRUE(second);
  EXPECT_GE(published_.at(*second) - published_.at(*first), 350ms) << "replayed faster than recorded";
  EXPECT_TRUE(published_.wait_for(neutral, *second + 1, 2s)) << "no neutral sample at the end of the recording";
}

TEST_F(JoystickSourceTest, StopPublishesANeutralSample) {
  ASSERT_EQ(mkfifo(path_.c_str(), 0600), 0);
  start();
  const int fd = open(path_.c_str(), O_WRONLY);
  ASSERT_GE(fd, 0);
  write_events(fd, {js(0, JS_EVENT_BUTTON, 0, 1)});
  const auto pressed = published_.wait_for([](const Joy& joy) { return joy.a == 1.0F; }, 0, 2s);
  ASSERT_TRUE(pressed);
  source_->stop();
  EXPECT_TRUE(published_.wait_for(neutral, *pressed + 1, 0ms));
  close(fd);
}

}  // namespace
}  // namespace robotd::joystick
