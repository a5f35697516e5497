// A device_call op's arguments, read with a JsonReader; finish() turns everything that was wrong
// into one error that names the op and says what it expects.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "robotd/driver/json_reader.hpp"
#include "robotd/result.hpp"

namespace robotd::driver {

class OpArguments {
 public:
  /// `usage` is the op's help line ("{"joint": 1..7, …}: what it does"); null `args` is {}.
  OpArguments(std::string_view op, const nlohmann::json& args, std::string_view usage);
  OpArguments(const OpArguments&) = delete;
  OpArguments& operator=(const OpArguments&) = delete;

  JsonReader& reader() { return reader_; }
  /// Reports unknown keys; "<op>: <problems> (expects <usage>)", or nullopt when all was well.
  std::optional<Error> finish();

 private:
  std::string op_;
  std::string usage_;
  std::vector<std::string> errors_;
  nlohmann::json args_;
  JsonReader reader_;
};

}  // namespace robotd::driver
