// Reading one command's fields with checks. A field that is missing, of the wrong type or out of
// range throws Refusal with a message naming it and what is expected; the dispatcher answers with
// the command's normal reply, its result field false and that message as "error".
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "trajectory_queue.hpp"

namespace robotd::realman::sim {

/// The controller says no: bad parameters, or a state in which the command cannot run.
class Refusal : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CommandRequest {
 public:
  CommandRequest(const nlohmann::json& body, ClientId client, std::int64_t now_ns)
      : body_(body), client_(client), now_ns_(now_ns) {}

  const nlohmann::json& body() const { return body_; }
  ClientId client() const { return client_; }
  std::int64_t now_ns() const { return now_ns_; }
  bool has(const char* key) const { return body_.contains(key); }

  std::int64_t integer(const char* key, std::int64_t min, std::int64_t max) const;
  std::optional<std::int64_t> optional_integer(const char* key, std::int64_t min, std::int64_t max) const;
  /// true/false, or 1/0 (the gripper doc types "block" as int).
  bool boolean(const char* key) const;
  std::optional<bool> optional_boolean(const char* key) const;
  /// Exactly `count` integers, each within [min, max]; `unit` names them in messages.
  std::vector<std::int64_t> integers(const char* key, std::size_t count, std::int64_t min, std::int64_t max,
                                     const char* unit) const;
  std::string string(const char* key) const;
  const nlohmann::json& object(const char* key) const;

 private:
  const nlohmann::json& field(const char* key, const std::string& expected) const;

  const nlohmann::json& body_;
  ClientId client_;
  std::int64_t now_ns_;
};

}  // namespace robotd::realman::sim
