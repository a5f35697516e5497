// The control channel's ops (README.md in this folder): what tests ask the simulator to report
// or to do wrong.
#include <algorithm>
#include <string>

#include <spdlog/spdlog.h>

#include "robotd/sim_control/control_request.hpp"
#include "simulator.hpp"

namespace robotd::xarm::sim {
namespace {

using nlohmann::json;
using sim_control::boolean_field;
using sim_control::expect_fields;
using sim_control::integer_field;
using sim_control::RequestError;

constexpr std::int64_t kMaxReplyCount = 1'000'000;
constexpr std::int64_t kGripperSlot = 8;
constexpr const char* kOps =
    "state, error, warning, servo_error, gripper_error, gripper_object, estop, drop_replies, garbage, disconnect, "
    "silence, "
    "set_joints";
/// A reply's transaction id no request used: half the id space away from the client's last one.
constexpr std::uint16_t kUnusedTransactionOffset = 0x8000;
constexpr std::uint8_t kGarbageRegister = 0x63;
constexpr std::uint16_t kBrokenLength = 0xFFFF;
constexpr std::string_view kGarbageText = "robotd-xarm-sim garbage";

std::string garbage_kind(const json& request) {
  const auto kind = request.find("kind");
  if (kind == request.end() || !kind->is_string() || (*kind != "frame" && *kind != "bytes")) {
    throw RequestError(
        "op \"garbage\" needs \"kind\": \"frame\" (a reply nobody asked for) or \"bytes\" (a "
        "length field of 0xFFFF, which breaks the framing)" +
        (kind == request.end() ? std::string() : ", not " + kind->dump()));
  }
  return kind->get<std::string>();
}

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
    // Every connection the kernel completed counts, accepted by the loop yet or not.
    accept_clients();
    for (ReportServer& report : reports_) report.serve();
    controller_.advance(monotonic_ns());
    json reply = {{"ok", true}};
    const auto dof = static_cast<std::int64_t>(controller_.model().dof);
    if (op == "state") {
      expect_fields(request, op, {});
      return state();
    }
    if (op == "error") {
      expect_fields(request, op, {"code"});
      controller_.latch_error(static_cast<int>(integer_field(request, op, "code", 0, 255)));
    } else if (op == "warning") {
      expect_fields(request, op, {"code"});
      controller_.set_warning(static_cast<int>(integer_field(request, op, "code", 0, 255)));
    } else if (op == "servo_error") {
      expect_fields(request, op, {"joint", "code"});
      const std::int64_t joint = integer_field(request, op, "joint", 1, kGripperSlot);
      if (joint > dof && joint != kGripperSlot) {
        throw RequestError("op \"servo_error\": \"joint\" must be 1 … " + std::to_string(dof) +
                           " (a joint) or 8 (the gripper), not " + std::to_string(joint));
      }
      controller_.set_servo_error(static_cast<std::size_t>(joint - 1),
                                  static_cast<int>(integer_field(request, op, "code", 0, 255)));
    } else if (op == "gripper_error") {
      expect_fields(request, op, {"code"});
      controller_.set_gripper_error(static_cast<int>(integer_field(request, op, "code", 0, 255)));
    } else if (op == "gripper_object") {
      expect_fields(request, op, {"width_pulses"});
      controller_.set_gripper_object(
          static_cast<int>(integer_field(request, op, "width_pulses", 0, kGripperMaxPulses)));
    } else if (op == "estop") {
      expect_fields(request, op, {"pressed"});
      controller_.set_estop(boolean_field(request, op, "pressed"));
    } else if (op == "drop_replies") {
      expect_fields(request, op, {"count"});
      replies_to_drop_ = static_cast<std::uint64_t>(integer_field(request, op, "count", 0, kMaxReplyCount));
    } else if (op == "garbage") {
      expect_fields(request, op, {"kind"});
      send_garbage(garbage_kind(request), reply);
    } else if (op == "disconnect") {
      expect_fields(request, op, {});
      std::size_t report_clients = 0;
      for (const ReportServer& report : reports_) report_clients += report.clients();
      reply["closed"] = clients_.size() + report_clients;
      disconnect_clients();
    } else if (op == "silence") {
      expect_fields(request, op, {"on"});
      reports_silenced_ = boolean_field(request, op, "on");
    } else if (op == "set_joints") {
      expect_fields(request, op, {"joints_rad"});
      if (auto moved = controller_.set_joints(joints_from(request, controller_.model().dof)); !moved) {
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

void Simulator::send_garbage(const std::string& kind, json& reply) {
  for (Client& client : clients_) {
    const auto transaction_id = static_cast<std::uint16_t>(client.last_transaction_id + kUnusedTransactionOffset);
    if (kind == "frame") {
      send(client, reply_frame(transaction_id, client.last_protocol, kGarbageRegister, controller_.status_byte()));
    } else {
      ByteWriter bytes;
      bytes.u16_be(transaction_id).u16_be(kProtocolPrivate).u16_be(kBrokenLength);
      for (const char c : kGarbageText) bytes.u8(static_cast<std::uint8_t>(c));
      client.output.append(bytes.data().begin(), bytes.data().end());
    }
    ++garbage_sent_;
  }
  reply["clients"] = clients_.size();
}

void Simulator::disconnect_clients() {
  for (Client& client : clients_) client.closed = true;
  drop_closed_clients();
  for (ReportServer& report : reports_) report.disconnect_all();
}

json Simulator::state() const {
  json state = controller_.state();
  std::size_t report_clients = 0;
  std::uint64_t reports_sent = 0;
  json ports = json::array();
  for (const ReportServer& report : reports_) {
    report_clients += report.clients();
    reports_sent += report.packets_sent();
    ports.push_back(
        {{"kind", report_kind_name(report.kind())}, {"clients", report.clients()}, {"sent", report.packets_sent()}});
  }
  state["command_clients"] = clients_.size();
  state["report_clients"] = report_clients;
  state["report_ports"] = ports;
  state["reports_sent"] = reports_sent;
  state["reports_silenced"] = reports_silenced_;
  state["replies_sent"] = replies_sent_;
  state["replies_dropped"] = replies_dropped_;
  state["drop_replies_pending"] = replies_to_drop_;
  state["feedback_frames_sent"] = feedback_frames_sent_;
  state["garbage_sent"] = garbage_sent_;
  return state;
}

}  // namespace robotd::xarm::sim
