// Scratch storage for building a C sample from C++ values. Sequences point straight into the
// C++ vectors (no copy); only arrays the C layout needs and C++ does not have (char* tables,
// nested struct arrays) are allocated here. The arena must outlive the dds_write call.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace robotd::wire {

class CArena {
 public:
  template <class E>
  E* array(std::size_t count) {
    auto block = std::make_unique<ArrayBlock<E>>(count);
    E* data = block->data.get();
    blocks_.push_back(std::move(block));
    return data;
  }

 private:
  struct Block {
    virtual ~Block() = default;
  };
  template <class E>
  struct ArrayBlock : Block {
    explicit ArrayBlock(std::size_t count) : data(std::make_unique<E[]>(count)) {}
    std::unique_ptr<E[]> data;
  };
  std::vector<std::unique_ptr<Block>> blocks_;
};

/// A C string view of `text` for a sample being written (Cyclone only reads it).
inline char* c_string(const std::string& text) { return const_cast<char*>(text.c_str()); }  // NOLINT

/// Points a generated dds_sequence_* at `values` without copying.
template <class Sequence, class E>
void view_sequence(Sequence& sequence, const std::vector<E>& values) {
  sequence._maximum = static_cast<std::uint32_t>(values.size());
  sequence._length = static_cast<std::uint32_t>(values.size());
  sequence._buffer = const_cast<E*>(values.data());  // NOLINT(cppcoreguidelines-pro-type-const-cast)
  sequence._release = false;
}

/// Builds a dds_sequence_string over `values`.
template <class Sequence>
void view_string_sequence(Sequence& sequence, const std::vector<std::string>& values, CArena& arena) {
  char** table = arena.array<char*>(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) table[i] = c_string(values[i]);
  sequence._maximum = static_cast<std::uint32_t>(values.size());
  sequence._length = static_cast<std::uint32_t>(values.size());
  sequence._buffer = table;
  sequence._release = false;
}

template <class E, class Sequence>
std::vector<E> copy_sequence(const Sequence& sequence) {
  if (sequence._buffer == nullptr) return {};
  return std::vector<E>(sequence._buffer, sequence._buffer + sequence._length);
}

inline std::string copy_string(const char* text) { return text != nullptr ? std::string(text) : std::string(); }

template <class Sequence>
std::vector<std::string> copy_string_sequence(const Sequence& sequence) {
  std::vector<std::string> out;
  out.reserve(sequence._length);
  for (std::uint32_t i = 0; i < sequence._length; ++i) out.push_back(copy_string(sequence._buffer[i]));
  return out;
}

}  // namespace robotd::wire
