#include "describe.hpp"

#include <ios>
#include <sstream>

namespace robotd::motion::detail {

std::string joint_name(std::size_t joint) { return "J" + std::to_string(joint + 1); }

std::string number(double value, int significant) {
  std::ostringstream text;
  text.precision(significant);
  text << value;
  return text.str();
}

std::string fixed(double value, int decimals) {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(decimals);
  text << value;
  return text.str();
}

}  // namespace robotd::motion::detail
