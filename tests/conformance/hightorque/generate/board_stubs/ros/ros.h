// Stand-in for the ROS 1 API the livelybot_serial sources use: parameters come from a map the
// harness fills, publishing does nothing, and sleeping runs the harness's board emulation (where
// the real SDK waits for its receive thread).
#pragma once

#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <type_traits>
#include <variant>

namespace ros {

using ParamValue = std::variant<int, bool, double, std::string>;
std::map<std::string, ParamValue>& params();
/// Called by Duration::sleep(): the harness lets the emulated board answer.
std::function<void()>& sleep_hook();

class Publisher {
 public:
  template <typename Message>
  void publish(const Message&) const {}
};

class NodeHandle {
 public:
  template <typename T>
  bool getParam(const std::string& key, T& out) const {
    const auto found = params().find(key);
    if (found == params().end()) return false;
    return std::visit(
        [&out](const auto& value) {
          using V = std::decay_t<decltype(value)>;
          if constexpr (std::is_same_v<V, std::string> != std::is_same_v<T, std::string>) {
            return false;
          } else {
            out = static_cast<T>(value);
            return true;
          }
        },
        found->second);
  }
  template <typename Message>
  Publisher advertise(const std::string&, int) const {
    return {};
  }
};

struct Time {
  static Time now() { return {}; }
  double toSec() const { return 0.0; }
};

struct Duration {
  explicit Duration(double) {}
  void sleep() const {
    if (sleep_hook()) sleep_hook()();
  }
};

inline bool ok() { return true; }

}  // namespace ros

#define ROS_INFO(...) ((void)0)
#define ROS_WARN(...) ((void)0)
#define ROS_ERROR(...) (std::fprintf(stderr, __VA_ARGS__), std::fputc('\n', stderr))
#define ROS_INFO_STREAM(x) ((void)0)
#define ROS_ERROR_STREAM(x) (std::cerr << x << '\n')
