// A warning that repeats is logged once per interval per key, with the count suppressed since,
// and the text of a suppressed one is never made (app/throttled_log.hpp).
#include "app/throttled_log.hpp"

#include <memory>
#include <sstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>

namespace robotd::app {
namespace {

using namespace std::chrono_literals;

// Routes spdlog's default logger into a string for the test's lifetime.
class CapturedLog {
 public:
  CapturedLog() : previous_(spdlog::default_logger()) {
    auto logger = std::make_shared<spdlog::logger>("captured", std::make_shared<spdlog::sinks::ostream_sink_st>(text_));
    logger->set_pattern("%l %v");
    spdlog::set_default_logger(logger);
  }
  CapturedLog(const CapturedLog&) = delete;
  CapturedLog& operator=(const CapturedLog&) = delete;
  ~CapturedLog() { spdlog::set_default_logger(previous_); }

  std::string text() const { return text_.str(); }

 private:
  std::ostringstream text_;
  std::shared_ptr<spdlog::logger> previous_;
};

TEST(ThrottledLog, OneLinePerIntervalPerKeyThenTheCountOfWhatWasSuppressed) {
  const CapturedLog captured;
  ThrottledLog log(50ms);
  for (int i = 0; i < 1000; ++i) log.warn("flood", "bad command");
  log.warn("other", "another kind");
  std::this_thread::sleep_for(60ms);
  log.warn("flood", "bad command");
  EXPECT_EQ(captured.text(),
            "warning bad command\n"
            "warning another kind\n"
            "warning bad command (999 similar messages suppressed)\n");
}

TEST(ThrottledLog, TheTextOfASuppressedMessageIsNeverMade) {
  const CapturedLog captured;
  ThrottledLog log(std::chrono::hours(1));
  int made = 0;
  for (int i = 0; i < 100; ++i) {
    log.log(spdlog::level::err, "flood", [&made] {
      ++made;
      return std::string("made once");
    });
  }
  EXPECT_EQ(made, 1);
  EXPECT_EQ(captured.text(), "error made once\n");
}

}  // namespace
}  // namespace robotd::app
