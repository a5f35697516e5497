// A DDS domain id no other test on this machine is using: an exclusive flock on
// /tmp/robotd-test-domain-<id>.lock, held for the test's lifetime, so tests run in parallel.
#pragma once

namespace robotd::testing {

class TestDomain {
 public:
  TestDomain();
  TestDomain(const TestDomain&) = delete;
  TestDomain& operator=(const TestDomain&) = delete;
  ~TestDomain();

  int id() const { return id_; }

 private:
  int id_ = -1;
  int lock_fd_ = -1;
};

}  // namespace robotd::testing
