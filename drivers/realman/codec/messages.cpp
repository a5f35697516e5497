// What one line from the controller is (§2): a reply named by its "command" or "state" value,
// the current_trajectory_state event (§3.2), or the UDP push (§6.2); and whether a reply says
// the command succeeded.
#include <string>
#include <string_view>
#include <utility>

#include "field_reader.hpp"
#include "realman_codec.hpp"

namespace robotd::realman {
namespace {

constexpr std::string_view kTrajectoryEventState = "current_trajectory_state";
constexpr std::string_view kRealtimePushState = "realtime_arm_joint_state";
constexpr int kLastDevice = static_cast<int>(Device::kExtension);

/// The value of a string field; "" when absent or not a string ({"state": true} names nothing).
std::string string_field(const nlohmann::json& object, std::string_view name) {
  const auto found = object.find(name);
  return found != object.end() && found->is_string() ? found->get<std::string>() : "";
}

}  // namespace

Result<Message> parse_message(std::string_view line) {
  auto parsed = parse_object(line);
  if (!parsed) return parsed.error();
  Message message;
  message.body = std::move(parsed).value();
  const std::string command = string_field(message.body, "command");
  const std::string state = string_field(message.body, "state");
  if (state == kTrajectoryEventState) {
    message.kind = MessageKind::kTrajectoryEvent;
    message.key = state;
  } else if (state == kRealtimePushState) {
    message.kind = MessageKind::kRealtimePush;
    message.key = state;
  } else if (!command.empty() || !state.empty()) {
    message.kind = MessageKind::kReply;
    message.key = command.empty() ? state : command;
  }
  return message;
}

Result<void> reply_success(const Message& reply, const ReplyShape& shape, std::string_view command) {
  std::string problem;
  FieldReader body(reply.body, "", problem);
  const bool succeeded = body.flag(shape.result_field);
  if (!problem.empty()) {
    return make_error(ErrorCode::kInvalidArgument, "the reply to " + std::string(command) + ": " + problem);
  }
  if (succeeded) return {};
  // The controller gives no reason; robotd's simulator adds an "error" text, which is passed on.
  std::string message = "the controller refused " + std::string(command);
  if (const std::string reason = string_field(reply.body, "error"); !reason.empty()) message += ": " + reason;
  return make_error(ErrorCode::kRefused, message);
}

Result<TrajectoryEvent> parse_trajectory_event(const Message& message) {
  std::string problem;
  FieldReader event(message.body, "", problem);
  TrajectoryEvent parsed;
  parsed.reached = event.flag("trajectory_state");
  parsed.device = static_cast<Device>(event.integer("device", 0, kLastDevice));
  // Absent in older examples: a single trajectory.
  parsed.more_segments = event.has("trajectory_connect") && event.flag("trajectory_connect");
  if (!problem.empty()) return make_error(ErrorCode::kInvalidArgument, "current_trajectory_state: " + problem);
  return parsed;
}

}  // namespace robotd::realman
