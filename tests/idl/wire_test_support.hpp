// Shared by the wire-library tests. Each test runs on a DDS domain no other test on this
// machine uses (tests/support/test_domain.hpp), with robotd's loopback defaults, so CTest can
// run them in parallel with each other and with the end-to-end tests.
#pragma once

#include <chrono>
#include <thread>

#include "test_domain.hpp"
#include "wire/dds_settings.hpp"

namespace robotd::testing {

/// A private domain, held for the object's lifetime, and the settings to join it.
class PrivateDomain {
 public:
  wire::DdsSettings settings() const {
    wire::DdsSettings settings;
    settings.domain_id = domain_.id();
    return settings;
  }

 private:
  TestDomain domain_;
};

/// Polls `condition` until it holds or `timeout` passes; returns its last value.
template <class Condition>
bool wait_until(Condition&& condition, std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= deadline) return condition();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

}  // namespace robotd::testing
