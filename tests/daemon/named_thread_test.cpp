// driver::NamedThread: the thread runs with the name and the stack size it was given.
#include "robotd/driver/named_thread.hpp"

#include <array>
#include <pthread.h>
#include <string>
#include <unistd.h>

#include <gtest/gtest.h>

namespace robotd::driver {
namespace {

struct Seen {
  std::string name;
  std::size_t stack_bytes = 0;
};

Seen run_and_look(const std::string& name, std::size_t stack_bytes) {
  Seen seen;
  NamedThread thread(
      name,
      [&seen] {
        std::array<char, 16> name_buffer{};
        pthread_getname_np(pthread_self(), name_buffer.data(), name_buffer.size());
        seen.name = name_buffer.data();
        pthread_attr_t attributes;
        pthread_getattr_np(pthread_self(), &attributes);
        pthread_attr_getstacksize(&attributes, &seen.stack_bytes);
        pthread_attr_destroy(&attributes);
      },
      stack_bytes);
  thread.join();
  return seen;
}

TEST(NamedThread, RunsWithItsNameAndStackSize) {
  const Seen seen = run_and_look("named-test", std::size_t{192} * 1024);
  EXPECT_EQ(seen.name, "named-test");
  EXPECT_EQ(seen.stack_bytes, std::size_t{192} * 1024);
}

TEST(NamedThread, DefaultStackIsTheDocumentedSize) {
  Seen seen;
  NamedThread thread("default-stack", [&seen] {
    pthread_attr_t attributes;
    pthread_getattr_np(pthread_self(), &attributes);
    pthread_attr_getstacksize(&attributes, &seen.stack_bytes);
    pthread_attr_destroy(&attributes);
  });
  thread.join();
  EXPECT_EQ(seen.stack_bytes, kThreadStackBytes);
}

TEST(NamedThread, StackRoundsUpToWholePagesAndNameIsCutTo15Characters) {
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  // Above the sanitizers' floor (ThreadSanitizer raises any stack below 128 KiB plus its TLS).
  const Seen seen = run_and_look("a-name-longer-than-15", std::size_t{300} * 1024 + 1);
  EXPECT_EQ(seen.stack_bytes, (std::size_t{300} * 1024 / page + 1) * page);
  EXPECT_EQ(seen.name, "a-name-longer-t");
}

TEST(NamedThread, MovesLikeStdThread) {
  int runs = 0;
  NamedThread first("mover", [&runs] { ++runs; });
  NamedThread second;
  EXPECT_FALSE(second.joinable());
  second = std::move(first);
  EXPECT_FALSE(first.joinable());  // NOLINT(bugprone-use-after-move): moved-from state is specified
  ASSERT_TRUE(second.joinable());
  second.join();
  EXPECT_FALSE(second.joinable());
  EXPECT_EQ(runs, 1);
}

}  // namespace
}  // namespace robotd::driver
