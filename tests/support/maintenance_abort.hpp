// Shows that a driver's maintenance gives up when robotd asks: runs recover() or reset_zero() on a
// thread, calls abort_maintenance() from the test's thread once it is under way (as robotd's RT
// loop does when an e-stop or a shutdown comes), and measures how soon it returns.
#pragma once

#include <chrono>
#include <future>
#include <iostream>
#include <string>
#include <thread>

#include "robotd/driver/driver.hpp"
#include "robotd/result.hpp"

namespace robotd::testing {

struct AbortedMaintenance {
  Result<void> result;
  bool returned_before_abort = false;  // the maintenance was over before the abort came
  std::chrono::microseconds abort_to_return{};
};

/// Starts `maintenance` (a call of `driver`'s recover() or reset_zero()) on a thread, waits
/// `under_way`, calls driver.abort_maintenance() and waits for the maintenance to return.
template <class Maintenance>
AbortedMaintenance abort_during(driver::Driver& driver, Maintenance maintenance, std::chrono::milliseconds under_way) {
  std::packaged_task<Result<void>()> task(std::move(maintenance));
  std::future<Result<void>> done = task.get_future();
  std::thread worker(std::move(task));
  AbortedMaintenance out{.result = Result<void>()};
  out.returned_before_abort = done.wait_for(under_way) == std::future_status::ready;
  const auto aborted_at = std::chrono::steady_clock::now();
  driver.abort_maintenance();
  done.wait();
  out.abort_to_return =
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - aborted_at);
  worker.join();
  out.result = done.get();
  return out;
}

/// Prints the measured figure for docs/drivers/<vendor>.md.
inline void print_abort_figure(const std::string& what, const AbortedMaintenance& aborted,
                               std::chrono::milliseconds normal_timeout) {
  std::cout << "[ measured ] " << what << ": abort_maintenance() to return "
            << static_cast<double>(aborted.abort_to_return.count()) / 1000.0 << " ms (its own timeout "
            << normal_timeout.count() << " ms)\n";
}

}  // namespace robotd::testing
