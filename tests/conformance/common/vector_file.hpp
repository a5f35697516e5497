#pragma once

// Reading the recorded conformance data of one vendor (tests/conformance/<vendor>/).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace robotd::conformance {

// The JSON file `name` in this vendor's data directory. Throws std::runtime_error naming the
// path when it is missing or not JSON, so a broken checkout fails loudly instead of passing
// with zero vectors.
nlohmann::json load_json(std::string_view name);

// Every line of the JSON-lines file `name` (blank lines skipped), same errors as load_json.
std::vector<nlohmann::json> load_json_lines(std::string_view name);

// "0a ff 80" or "0aff80" → bytes; throws std::invalid_argument on anything else.
std::vector<std::uint8_t> hex_bytes(std::string_view hex);

// Bytes → "0a ff 80", the form the data files and failure messages use.
std::string hex_text(const std::uint8_t* data, std::size_t size);
inline std::string hex_text(const std::vector<std::uint8_t>& bytes) { return hex_text(bytes.data(), bytes.size()); }

}  // namespace robotd::conformance
