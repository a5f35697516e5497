#include "realman_transcript.hpp"

#include <algorithm>
#include <stdexcept>

#include "vector_file.hpp"

namespace robotd::realman::conformance {
namespace {

Session& session_named(std::vector<Session>& sessions, const std::string& name) {
  const auto found = std::ranges::find(sessions, name, &Session::name);
  if (found != sessions.end()) return *found;
  Session& added = sessions.emplace_back();
  added.name = name;
  return added;
}

Connection& connection_with(Session& session, int id) {
  const auto found = std::ranges::find(session.connections, id, &Connection::id);
  if (found != session.connections.end()) return *found;
  Connection& added = session.connections.emplace_back();
  added.id = id;
  return added;
}

}  // namespace

std::string message_key(const nlohmann::json& message) {
  for (const char* key : {"command", "state"}) {
    if (message.is_object() && message.contains(key) && message[key].is_string()) return message[key];
  }
  return "";
}

std::vector<Session> load_sessions() {
  std::vector<Session> sessions;
  for (const nlohmann::json& line : robotd::conformance::load_json_lines("transcript.jsonl")) {
    Session& session = session_named(sessions, line.at("session"));
    const std::string direction = line.at("direction");
    const std::string text = line.at("text");
    if (direction == "push") {
      session.pushes.push_back(text);
      continue;
    }
    Connection& connection = connection_with(session, line.at("connection"));
    if (direction == "request") {
      connection.exchanges.emplace_back().request = text;
    } else if (direction == "reply") {
      if (connection.exchanges.empty()) throw std::runtime_error("transcript.jsonl: a reply before any request");
      connection.exchanges.back().replies.push_back(text);
    } else {
      throw std::runtime_error("transcript.jsonl: unknown direction \"" + direction + "\"");
    }
  }
  const nlohmann::json provenance = robotd::conformance::load_json("provenance.json");
  for (const nlohmann::json& recorded : provenance.at("sessions")) {
    session_named(sessions, recorded.at("name")).sim_options = recorded.at("simulator_options");
  }
  for (const nlohmann::json& result : robotd::conformance::load_json_lines("sdk_results.jsonl")) {
    if (result.at("call") == "rm_movej_canfd") {
      session_named(sessions, result.at("session")).stream_period_s = result.at("args").at("period_s");
    }
  }
  return sessions;
}

}  // namespace robotd::realman::conformance
