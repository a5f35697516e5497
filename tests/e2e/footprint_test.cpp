// End to end: robotd's memory footprint, read from /proc of the running daemon. Every thread has
// the stack robotd gives it (not the 8 MiB process default) and only the RT loop's stack is
// prefaulted, though mlockall now locks pages only as they are touched; the code and constants
// of every loaded object are resident all the same.
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "config/config.hpp"
#include "robotd/driver/named_thread.hpp"
#include "robotd_fixture.hpp"
#include "rt/realtime_thread.hpp"
#include "sanitizer_build.hpp"

namespace robotd::testing {
namespace {

using namespace std::chrono_literals;

constexpr std::size_t kKiB = 1024;

struct Mapping {
  std::uintptr_t start = 0;
  std::uintptr_t end = 0;
  std::string path;  // of a mapped file; empty or [name] otherwise
  std::size_t resident_bytes = 0;
};

struct ThreadStack {
  std::string name;
  std::size_t size_bytes = 0;
  std::size_t resident_bytes = 0;
};

std::string read_text(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

std::uintptr_t hex(std::string_view text) {
  std::uintptr_t value = 0;
  std::from_chars(text.data(), text.data() + text.size(), value, 16);
  return value;
}

std::vector<Mapping> mappings(pid_t pid) {
  std::vector<Mapping> maps;
  std::istringstream smaps(read_text("/proc/" + std::to_string(pid) + "/smaps"));
  for (std::string line; std::getline(smaps, line);) {
    const std::size_t dash = line.find('-');
    const std::size_t space = line.find(' ');
    if (dash != std::string::npos && space != std::string::npos && dash < space) {
      std::istringstream fields(line);
      std::string range, permissions, offset, device, inode, path;
      fields >> range >> permissions >> offset >> device >> inode >> path;
      maps.push_back({hex(std::string_view(line).substr(0, dash)),
                      hex(std::string_view(line).substr(dash + 1, space - dash - 1)), path, 0});
    } else if (line.starts_with("Rss:") && !maps.empty()) {
      maps.back().resident_bytes = std::stoul(line.substr(4)) * kKiB;
    }
  }
  return maps;
}

/// The stack of every thread but the main one: the mapping that holds the thread's stack pointer,
/// which /proc/<pid>/task/<tid>/syscall shows while the thread waits in a system call (robotd's
/// threads nearly always do; one that is running is read again). nullopt if some thread was
/// never seen waiting before the deadline.
std::optional<std::vector<ThreadStack>> thread_stacks(pid_t pid) {
  const std::filesystem::path tasks = "/proc/" + std::to_string(pid) + "/task";
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (std::chrono::steady_clock::now() < deadline) {
    const std::vector<Mapping> maps = mappings(pid);
    std::vector<ThreadStack> stacks;
    bool all_waiting = true;
    for (const auto& task : std::filesystem::directory_iterator(tasks)) {
      if (task.path().filename() == std::to_string(pid)) continue;  // the main thread's stack grows on demand
      std::istringstream syscall(read_text(task.path() / "syscall"));
      std::vector<std::string> fields;
      for (std::string field; syscall >> field;) fields.push_back(field);
      if (fields.size() < 3) {  // "running", or the thread has just ended
        all_waiting = false;
        break;
      }
      const std::uintptr_t stack_pointer = hex(std::string_view(fields[fields.size() - 2]).substr(2));
      ThreadStack stack{read_text(task.path() / "comm"), 0, 0};
      stack.name.erase(stack.name.find_last_not_of('\n') + 1);
      for (const Mapping& map : maps) {
        if (map.start <= stack_pointer && stack_pointer < map.end) {
          stack.size_bytes = map.end - map.start;
          stack.resident_bytes = map.resident_bytes;
        }
      }
      stacks.push_back(stack);
    }
    if (all_waiting) return stacks;
    std::this_thread::sleep_for(10ms);
  }
  return std::nullopt;
}

/// The stack a thread was given. A sanitizer's runtime may enlarge a small one to make room for its
/// own thread-local data, but not to the process default (RLIMIT_STACK), which std::thread takes.
void expect_stack_of(const ThreadStack& stack, std::size_t given) {
  if (!kSanitizerBuild) {
    EXPECT_EQ(stack.size_bytes, given) << stack.name;
    return;
  }
  EXPECT_GE(stack.size_bytes, given) << stack.name;
  rlimit limit{};
  if (getrlimit(RLIMIT_STACK, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    EXPECT_LT(stack.size_bytes, limit.rlim_cur) << stack.name << " has the process default stack";
  }
}

bool is_cyclone_thread(const std::string& name) {
  return name == "recv" || name == "tev" || name == "gc" || name == "dq.builtins" || name == "dq.user";
}

class FootprintTest : public RobotdTest {};

TEST_F(FootprintTest, EveryThreadHasTheStackRobotdGivesItAndOnlyTheLoopsArePrefaulted) {
  start_robotd();
  Session session = acquire_device("arm");
  ASSERT_TRUE(session.send_positions({0.1F, 0, 0, 0, 0, 0}));
  ASSERT_TRUE(wait_for_joints([](const JointState& s) { return std::fabs(s.position[0] - 0.1) < 0.01; }, 10s));

  const auto stacks = thread_stacks(robotd_->pid());
  ASSERT_TRUE(stacks) << "some robotd thread was never seen waiting in a system call";
  bool saw_loop = false;
  bool saw_cyclone = false;
  for (const ThreadStack& stack : *stacks) {
    std::printf("[ measured ] thread %-15s stack %5zu KiB, resident %4zu KiB\n", stack.name.c_str(),
                stack.size_bytes / kKiB, stack.resident_bytes / kKiB);
    if (stack.name.starts_with("rt-")) {
      saw_loop = true;
      expect_stack_of(stack, rt::kLoopStackBytes);
      EXPECT_GE(stack.resident_bytes, rt::kStackPrefaultBytes) << stack.name << ": the loop's stack is not prefaulted";
      continue;
    }
    saw_cyclone = saw_cyclone || is_cyclone_thread(stack.name);
    expect_stack_of(stack,
                    is_cyclone_thread(stack.name) ? config::kCycloneThreadStackBytes : driver::kThreadStackBytes);
    EXPECT_LT(stack.resident_bytes, stack.size_bytes) << stack.name << ": its whole stack is resident";
  }
  EXPECT_TRUE(saw_loop) << "no rt-arm thread";
  EXPECT_TRUE(saw_cyclone) << "none of Cyclone DDS's threads";
}

TEST_F(FootprintTest, EveryLoadedObjectIsWhollyResidentOnceTheLoopsRun) {
  start_robotd();
  const std::string status = read_text("/proc/" + std::to_string(robotd_->pid()) + "/status");
  const std::size_t locked = status.find("VmLck:");
  ASSERT_NE(locked, std::string::npos);
  // Without the right to lock memory, or under a sanitizer (which makes mlock a no-op), nothing is.
  if (std::stoul(status.substr(locked + 6)) == 0) GTEST_SKIP() << "robotd could not lock memory here";
  std::size_t objects = 0;
  for (const Mapping& map : mappings(robotd_->pid())) {
    if (map.path.empty() || map.path.front() != '/') continue;  // anonymous, [heap], [vdso] …
    ++objects;
    EXPECT_EQ(map.resident_bytes, map.end - map.start)
        << map.path << ": part of a loaded object is not resident; a loop running that code or "
        << "constant for the first time would page-fault";
  }
  EXPECT_GT(objects, 0U);
}

}  // namespace
}  // namespace robotd::testing
