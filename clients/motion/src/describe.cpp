#include "describe.hpp"

#include <ios>
#include <numbers>
#include <sstream>

namespace robotd::motion::detail {

std::string joint_name(std::size_t joint) { return "J" + std::to_string(joint + 1); }

double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }

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
