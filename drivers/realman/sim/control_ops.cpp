// The control channel's ops (README.md in this folder): what tests ask the simulator to report
// or to do wrong.
#include <algorithm>
#include <string>

#include <spdlog/spdlog.h>

#include "robotd/sim_control/control_request.hpp"
#include "simulator.hpp"

namespace robotd::realman::sim {
namespace {

using nlohmann::json;
using sim_control::boolean_field;
using sim_control::expect_fields;
using sim_control::integer_field;
using sim_control::RequestError;

constexpr std::int64_t kMaxReplyCount = 1'000'000;
constexpr const char* kOps =
    "state, raise_error, joint_error, clear, silence, drop_replies, garbage, disconnect, place_object, "
    "remove_object, set_joints";
constexpr std::string_view kGarbageLine = "robotd-realman-sim garbage: }{ not JSON\r\n";
constexpr std::string_view kGarbageDatagram = "\x01\x02 robotd-realman-sim garbage: not a push\r\n";

JointValues joints_from(const json& request, std::size_t dof) {
  const std::vector<double> numbers = sim_control::numbers_field(request, "set_joints", "joints_rad", dof, "rad");
  JointValues joints{};
  std::copy(numbers.begin(), numbers.end(), joints.begin());
  return joints;
}

}  // namespace

json Simulator::control(const json& request) {
  try {
    const std::string op = sim_control::op_of(request, kOps);
    const std::int64_t now = monotonic_ns();
    controller_.advance(now);
    json reply = {{"ok", true}};
    Arm& arm = controller_.arm();
    if (op == "state") {
      expect_fields(request, op, {});
      return state(now);
    }
    if (op == "raise_error") {
      expect_fields(request, op, {"code"});
      arm.raise_error(static_cast<std::uint16_t>(integer_field(request, op, "code", 1, 0xFFFF)));
    } else if (op == "joint_error") {
      expect_fields(request, op, {"joint", "bits"});
      const auto joint = integer_field(request, op, "joint", 1, static_cast<std::int64_t>(arm.dof()));
      arm.set_joint_error(static_cast<std::size_t>(joint - 1),
                          static_cast<std::uint16_t>(integer_field(request, op, "bits", 0, 0xFFFF)));
    } else if (op == "clear") {
      expect_fields(request, op, {});
      arm.clear_system_errors();
      for (std::size_t j = 0; j < arm.dof(); ++j) arm.set_joint_error(j, 0);
    } else if (op == "silence") {
      expect_fields(request, op, {"on"});
      push_silenced_ = boolean_field(request, op, "on");
    } else if (op == "drop_replies") {
      expect_fields(request, op, {"count"});
      replies_to_drop_ = static_cast<std::uint64_t>(integer_field(request, op, "count", 0, kMaxReplyCount));
    } else if (op == "garbage") {
      expect_fields(request, op, {});
      send_garbage(reply);
    } else if (op == "disconnect") {
      expect_fields(request, op, {});
      reply["closed"] = clients_.size();
      disconnect_clients();
    } else if (op == "place_object") {
      expect_fields(request, op, {"opening"});
      controller_.gripper().place_object(static_cast<int>(integer_field(request, op, "opening", 0, 1000)));
    } else if (op == "remove_object") {
      expect_fields(request, op, {});
      controller_.gripper().remove_object();
    } else if (op == "set_joints") {
      expect_fields(request, op, {"joints_rad"});
      if (auto moved = arm.teleport(joints_from(request, arm.dof())); !moved) {
        throw RequestError("op \"set_joints\": " + moved.error().message);
      }
    } else {
      throw RequestError("unknown op \"" + op + "\": expected one of " + kOps);
    }
    if (!options_.quiet) spdlog::info("control: {}", request.dump());
    return reply;
  } catch (const RequestError& error) {
    return sim_control::error_reply(error.what());
  } catch (const std::exception& error) {
    return sim_control::error_reply(std::string("the simulator failed on this request: ") + error.what());
  }
}

void Simulator::send_garbage(json& reply) {
  for (Client& client : clients_) {
    client.output += kGarbageLine;
    ++garbage_sent_;
  }
  reply["lines"] = clients_.size();
  const auto destination = push_destination();
  const bool datagram = destination && send_datagram(*destination, kGarbageDatagram);
  if (datagram) ++garbage_sent_;
  reply["datagram"] = datagram;
}

void Simulator::disconnect_clients() {
  for (Client& client : clients_) client.closed = true;
  drop_closed_clients();
}

json Simulator::state(std::int64_t now_ns) const {
  json state = controller_.state(now_ns);
  const auto destination = push_destination();
  state["push"]["active"] = controller_.pushing() && !push_silenced_;
  state["push"]["silenced"] = push_silenced_;
  state["push"]["destination"] = destination ? json(destination->to_string()) : json(nullptr);
  state["push"]["sent"] = pushes_sent_;
  state["push"]["failed"] = push_failures_;
  state["port"] = options_.port;
  state["clients"] = clients_.size();
  state["clients_accepted"] = clients_accepted_;
  state["replies_sent"] = replies_sent_;
  state["replies_dropped"] = replies_dropped_;
  state["drop_replies_pending"] = replies_to_drop_;
  state["events_sent"] = events_sent_;
  state["garbage_sent"] = garbage_sent_;
  return state;
}

}  // namespace robotd::realman::sim
