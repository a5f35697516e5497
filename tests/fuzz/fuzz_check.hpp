// FUZZ_CHECK(condition): an invariant of a fuzz target. Unlike assert() it stays on in release
// builds, so the replay tests check it too; a violation aborts, which libFuzzer reports as a
// crash and saves the input.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace robotd::fuzz {

/// Text a device sent that robotd shows or puts into JSON (whose dump() throws on bytes that are
/// not UTF-8) must have been made printable by the codec.
inline bool is_printable_ascii(std::string_view text) {
  return std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7F; });
}

/// Every value a decoder produced is a number (no NaN or infinity got through).
template <std::size_t N>
bool all_finite(const std::array<double, N>& values) {
  return std::all_of(values.begin(), values.end(), [](double value) { return std::isfinite(value); });
}

[[noreturn]] inline void check_failed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: fuzz invariant failed: %s\n", file, line, condition);
  std::abort();
}

}  // namespace robotd::fuzz

#define FUZZ_CHECK(condition) \
  ((condition) ? static_cast<void>(0) : ::robotd::fuzz::check_failed(#condition, __FILE__, __LINE__))
