#pragma once

// The recorded RM_API2 sessions (transcript.jsonl, written by generate/generate.py) as exchanges:
// each request the vendor SDK sent and the lines the controller sent back before its next one.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace robotd::realman::conformance {

struct Exchange {
  std::string request;               // the line as the SDK sent it, without CR LF
  std::vector<std::string> replies;  // replies and events, in the order they came
};

struct Connection {
  int id = 0;
  std::vector<Exchange> exchanges;
};

struct Session {
  std::string name;                      // "gen3", "gen4"
  std::vector<std::string> sim_options;  // how the simulator ran ("--generation", "3")
  std::vector<Connection> connections;   // in the order they opened
  std::vector<std::string> pushes;       // the UDP datagrams kept
  double stream_period_s = 0;            // the movej_canfd stream's period (0: none)
};

/// Every session of transcript.jsonl with its settings from provenance.json and sdk_results.jsonl.
std::vector<Session> load_sessions();

/// The "command" or "state" value that names a message ("" if neither is a string).
std::string message_key(const nlohmann::json& message);

}  // namespace robotd::realman::conformance
