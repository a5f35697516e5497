#include "command_cache.hpp"

#include <algorithm>

namespace robotd::xarm::sim {
namespace {

constexpr int kStarted = 1;
constexpr int kFinished = 2;
constexpr int kCodeOk = 0;
constexpr int kCodeDiscarded = 2;

}  // namespace

JointValues CommandCache::next_start(const JointValues& position) const {
  const auto last_move = std::find_if(commands_.rbegin(), commands_.rend(),
                                      [](const CachedCommand& command) { return command.path.has_value(); });
  return last_move == commands_.rend() ? position : last_move->path->end();
}

void CommandCache::push(CachedCommand command) { commands_.push_back(std::move(command)); }

bool CommandCache::finished(const CachedCommand& command) const {
  if (command.path) return running_->progress->done();
  return running_->slept_s >= command.sleep_s;
}

std::optional<JointValues> CommandCache::advance(double dt_s, std::vector<CacheEvent>& events) {
  std::optional<JointValues> joints;
  while (!commands_.empty()) {
    CachedCommand& command = commands_.front();
    if (!running_) {
      if (braking_) return joints;  // held: nothing new starts
      running_ = Running{};
      if (command.path) running_->progress.emplace(command.path->length(), command.speed, command.acceleration);
      events.push_back(CacheEvent{.origin = command.origin, .type = kStarted, .code = kCodeOk});
    }
    if (command.path) {
      running_->progress->advance(dt_s);
      joints = command.path->at(running_->progress->position());
    } else if (!braking_) {
      running_->slept_s += dt_s;
    }
    if (!finished(command)) return joints;
    // Whatever time this command did not need goes to the next one.
    dt_s = command.path ? 0.0 : running_->slept_s - command.sleep_s;
    events.push_back(CacheEvent{.origin = command.origin, .type = kFinished, .code = kCodeOk});
    commands_.pop_front();
    running_.reset();
  }
  return joints;
}

JointValues CommandCache::velocity() const {
  if (!running_ || !running_->progress) return {};
  const PathProgress& progress = *running_->progress;
  return commands_.front().path->velocity(progress.position(), progress.speed());
}

void CommandCache::brake() {
  braking_ = true;
  if (running_ && running_->progress) running_->progress->brake();
}

void CommandCache::resume() {
  braking_ = false;
  if (running_ && running_->progress) running_->progress->resume();
}

bool CommandCache::at_rest() const {
  if (!running_ || !running_->progress) return true;
  return braking_ && running_->progress->halted();
}

void CommandCache::clear(std::vector<CacheEvent>& events) {
  for (const CachedCommand& command : commands_) {
    events.push_back(CacheEvent{.origin = command.origin, .type = kFinished, .code = kCodeDiscarded});
  }
  commands_.clear();
  running_.reset();
  braking_ = false;
}

}  // namespace robotd::xarm::sim
