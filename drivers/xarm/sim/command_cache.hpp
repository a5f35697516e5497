// The controller's command cache (spec §2.6, §9): planned moves and sleeps queued by move_line,
// move_joint, move_gohome, sleep_instruction …, run one after another. Each is planned when it is
// queued, from where the one before it ends. The cache can brake the move in progress to rest on
// its path (pause, decelerated stop), resume it, and be cleared. What starts, ends or is
// discarded is reported as events, for the motion-feedback frames (§2.5).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "codec/xarm_codec.hpp"
#include "path_progress.hpp"
#include "planned_path.hpp"

namespace robotd::xarm::sim {

using ClientId = std::uint64_t;

/// Which request a cached command came from.
struct CommandOrigin {
  ClientId client = 0;
  std::uint16_t transaction_id = 0;
  std::uint16_t protocol = kProtocolPrivate;
  std::uint8_t reg = 0;
  std::uint16_t task_id = 0;  // numbers the cached commands, from 1
  /// The connection's set_feedback_type when the request arrived: the SDK sets a mask, sends
  /// the move and restores the mask before the move ends, and still waits for its frame.
  std::uint8_t feedback_types = 0;
};

struct CachedCommand {
  CommandOrigin origin;
  std::optional<PlannedPath> path;  // a move
  double speed = 0;                 // in the path's unit per second
  double acceleration = 0;
  double sleep_s = 0;  // a sleep_instruction (no path)
};

/// A cached command started (1), finished (2, code 0) or was discarded (2, code 2): §2.5's types.
struct CacheEvent {
  CommandOrigin origin;
  int type = 0;
  int code = 0;
};

class CommandCache {
 public:
  static constexpr std::size_t kCapacity = 1024;  // the SDK's limit; beyond it warning 11

  std::size_t size() const { return commands_.size(); }
  bool empty() const { return commands_.empty(); }
  bool full() const { return commands_.size() >= kCapacity; }
  /// Where a move queued now starts: the end of the last queued move, else `position`.
  JointValues next_start(const JointValues& position) const;

  void push(CachedCommand command);
  /// Runs the commands for `dt_s`: the joints on the path of the move in progress (nullopt when
  /// none moves). Starts and ends are appended to `events`.
  std::optional<JointValues> advance(double dt_s, std::vector<CacheEvent>& events);
  /// The joints' velocity on the move in progress, as its profile has it now (0 when none).
  JointValues velocity() const;
  /// The move in progress decelerates to rest on its path; a sleep stops counting. Nothing new
  /// starts until resume().
  void brake();
  void resume();
  bool braking() const { return braking_; }
  /// Braked and at rest (or nothing in progress).
  bool at_rest() const;
  /// Drops everything; a discarded event for each command.
  void clear(std::vector<CacheEvent>& events);

 private:
  struct Running {
    std::optional<PathProgress> progress;  // a move
    double slept_s = 0;                    // a sleep
  };

  bool finished(const CachedCommand& command) const;

  std::deque<CachedCommand> commands_;
  std::optional<Running> running_;  // the front command, once started
  bool braking_ = false;
};

}  // namespace robotd::xarm::sim
