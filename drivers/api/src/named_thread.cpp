#include "robotd/driver/named_thread.hpp"

#include <exception>
#include <limits.h>
#include <memory>
#include <system_error>
#include <unistd.h>
#include <utility>

namespace robotd::driver {
namespace {

struct Start {
  std::string name;
  std::function<void()> body;
};

void* run(void* argument) noexcept {
  const std::unique_ptr<Start> start(static_cast<Start*>(argument));
  pthread_setname_np(pthread_self(), start->name.substr(0, 15).c_str());
  start->body();  // an exception leaving it terminates the program, as on a std::thread
  return nullptr;
}

std::size_t whole_pages(std::size_t bytes) {
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  const auto minimum = static_cast<std::size_t>(PTHREAD_STACK_MIN);
  const std::size_t at_least = bytes < minimum ? minimum : bytes;
  return (at_least + page - 1) / page * page;
}

}  // namespace

NamedThread::NamedThread(const std::string& name, std::function<void()> body, std::size_t stack_bytes) {
  pthread_attr_t attributes;
  pthread_attr_init(&attributes);
  int rc = pthread_attr_setstacksize(&attributes, whole_pages(stack_bytes));
  auto start = std::make_unique<Start>(Start{name, std::move(body)});
  if (rc == 0) rc = pthread_create(&handle_, &attributes, run, start.get());
  pthread_attr_destroy(&attributes);
  if (rc != 0) throw std::system_error(rc, std::generic_category(), "cannot start thread " + name);
  [[maybe_unused]] Start* owned_by_the_thread = start.release();
  joinable_ = true;
}

NamedThread::NamedThread(NamedThread&& other) noexcept
    : handle_(other.handle_), joinable_(std::exchange(other.joinable_, false)) {}

NamedThread& NamedThread::operator=(NamedThread&& other) noexcept {
  if (joinable_) std::terminate();
  handle_ = other.handle_;
  joinable_ = std::exchange(other.joinable_, false);
  return *this;
}

NamedThread::~NamedThread() {
  if (joinable_) std::terminate();
}

void NamedThread::join() {
  if (!joinable_) throw std::system_error(std::make_error_code(std::errc::invalid_argument), "join: not joinable");
  const int rc = pthread_join(handle_, nullptr);
  if (rc != 0) throw std::system_error(rc, std::generic_category(), "join");
  joinable_ = false;
}

}  // namespace robotd::driver
