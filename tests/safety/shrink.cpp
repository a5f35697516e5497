#include "shrink.hpp"

#include <algorithm>
#include <cctype>
#include <string>

namespace robotd::safety {
namespace {

// What kind of violation it is: the invariant and its reason, without the numbers.
std::string signature(const Violation& violation) {
  std::string text = violation.invariant + ": " + violation.detail.substr(0, violation.detail.find('['));
  std::string kind;
  for (const char c : text) {
    if (std::isdigit(static_cast<unsigned char>(c)) == 0) kind += c;
  }
  return kind;
}

class Shrinker {
 public:
  Shrinker(const Scenario& failing, const RunResult& failure, Runner runner, std::size_t max_replays)
      : run_(runner),
        best_(failing),
        best_result_(failure),
        kind_(signature(*failure.violation)),
        budget_(max_replays) {
    best_.events.resize(std::min(best_.events.size(), failure.events_run));
  }

  ShrinkResult shrink() {
    remove_chunks();
    merge_tick_runs();
    shorten_tick_runs();
    remove_chunks();
    return ShrinkResult{best_, best_result_, replays_};
  }

 private:
  // Replays `events`; keeps them as the best so far if they still break the same invariant.
  bool still_fails(std::vector<Event> events) {
    if (replays_ >= budget_) return false;
    ++replays_;
    Scenario candidate{best_.device, std::move(events)};
    RunResult result = run_(candidate, nullptr);
    if (!result.violation || signature(*result.violation) != kind_) return false;
    candidate.events.resize(std::min(candidate.events.size(), result.events_run));
    best_ = std::move(candidate);
    best_result_ = std::move(result);
    return true;
  }

  void remove_chunks() {
    std::size_t chunks = 2;
    while (best_.events.size() >= 2 && replays_ < budget_) {
      const std::size_t size = best_.events.size();
      const std::size_t chunk = std::max<std::size_t>(1, size / chunks);
      bool removed = false;
      for (std::size_t start = 0; start < best_.events.size(); start += chunk) {
        std::vector<Event> events = best_.events;
        const std::size_t end = std::min(events.size(), start + chunk);
        events.erase(events.begin() + static_cast<std::ptrdiff_t>(start),
                     events.begin() + static_cast<std::ptrdiff_t>(end));
        if (still_fails(std::move(events))) {
          removed = true;
          break;
        }
      }
      if (removed) {
        chunks = std::max<std::size_t>(2, chunks - 1);
      } else if (chunk == 1) {
        return;
      } else {
        chunks = std::min(best_.events.size(), chunks * 2);
      }
    }
  }

  // Consecutive ticks become one run on time, where the failure allows.
  void merge_tick_runs() {
    for (std::size_t i = 0; i + 1 < best_.events.size() && replays_ < budget_; ++i) {
      if (best_.events[i].kind != Event::Kind::kTick) continue;
      std::size_t end = i + 1;
      int count = best_.events[i].count;
      while (end < best_.events.size() && best_.events[end].kind == Event::Kind::kTick)
        count += best_.events[end++].count;
      if (end == i + 1) continue;
      std::vector<Event> events = best_.events;
      events[i].count = count;
      events[i].latency_us = 0;
      events.erase(events.begin() + static_cast<std::ptrdiff_t>(i + 1),
                   events.begin() + static_cast<std::ptrdiff_t>(end));
      (void)still_fails(std::move(events));
    }
  }

  void shorten_tick_runs() {
    for (std::size_t i = 0; i < best_.events.size() && replays_ < budget_; ++i) {
      while (best_.events[i].kind == Event::Kind::kTick && best_.events[i].count > 1) {
        std::vector<Event> events = best_.events;
        events[i].count /= 2;
        if (!still_fails(std::move(events))) break;
      }
      if (i < best_.events.size() && best_.events[i].kind == Event::Kind::kTick && best_.events[i].latency_us != 0) {
        std::vector<Event> events = best_.events;
        events[i].latency_us = 0;
        (void)still_fails(std::move(events));
      }
    }
  }

  Runner run_;
  Scenario best_;
  RunResult best_result_;
  std::string kind_;
  std::size_t budget_;
  std::size_t replays_ = 0;
};

}  // namespace

ShrinkResult shrink(const Scenario& failing, const RunResult& failure, Runner run, std::size_t max_replays) {
  return Shrinker(failing, failure, run, max_replays).shrink();
}

}  // namespace robotd::safety
