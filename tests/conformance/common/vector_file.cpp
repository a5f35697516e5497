#include "vector_file.hpp"

#include <fstream>
#include <stdexcept>

#ifndef ROBOTD_CONFORMANCE_DATA_DIR
#error "ROBOTD_CONFORMANCE_DATA_DIR names the vendor's data directory (robotd_add_conformance)"
#endif

namespace robotd::conformance {
namespace {

std::string data_path(std::string_view name) {
  return std::string(ROBOTD_CONFORMANCE_DATA_DIR) + "/" + std::string(name);
}

std::ifstream open(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw std::runtime_error("conformance data " + path + " cannot be opened");
  }
  return in;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

nlohmann::json load_json(std::string_view name) {
  const std::string path = data_path(name);
  std::ifstream in = open(path);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error("conformance data " + path + " is not JSON: " + e.what());
  }
}

std::vector<nlohmann::json> load_json_lines(std::string_view name) {
  const std::string path = data_path(name);
  std::ifstream in = open(path);
  std::vector<nlohmann::json> lines;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      lines.push_back(nlohmann::json::parse(line));
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error("conformance data " + path + " line " + std::to_string(number) +
                               " is not JSON: " + e.what());
    }
  }
  return lines;
}

std::vector<std::uint8_t> hex_bytes(std::string_view hex) {
  std::vector<std::uint8_t> bytes;
  int high = -1;
  for (const char c : hex) {
    if (c == ' ') continue;
    const int digit = hex_digit(c);
    if (digit < 0) {
      throw std::invalid_argument("'" + std::string(hex) + "' is not hex bytes (expected e.g. \"0a ff\")");
    }
    if (high < 0) {
      high = digit;
    } else {
      bytes.push_back(static_cast<std::uint8_t>(high << 4 | digit));
      high = -1;
    }
  }
  if (high >= 0) {
    throw std::invalid_argument("'" + std::string(hex) + "' has an odd number of hex digits");
  }
  return bytes;
}

std::string hex_text(const std::uint8_t* data, std::size_t size) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text;
  text.reserve(size * 3);
  for (std::size_t i = 0; i < size; ++i) {
    if (i > 0) text += ' ';
    text += kDigits[data[i] >> 4];
    text += kDigits[data[i] & 0x0F];
  }
  return text;
}

}  // namespace robotd::conformance
