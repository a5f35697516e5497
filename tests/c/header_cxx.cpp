// Compiled only: robotd/robotd.h is valid C++20 with robotd's warnings, with C linkage, and its
// enums have a fixed underlying type (so any int32_t a C caller passes is a value C++ may read).
#include <cstdint>
#include <robotd/robotd.h>
#include <type_traits>

static_assert(std::is_same_v<std::underlying_type_t<robotd_status>, std::int32_t>);
static_assert(std::is_same_v<std::underlying_type_t<robotd_control_mode>, std::int32_t>);
static_assert(std::is_same_v<std::underlying_type_t<robotd_behavior>, std::int32_t>);
static_assert(std::is_same_v<std::underlying_type_t<robotd_device_state>, std::int32_t>);
static_assert(std::is_standard_layout_v<robotd_joint_state> && std::is_trivially_copyable_v<robotd_joint_state>);
static_assert(std::is_same_v<decltype(&robotd_last_error), const char* (*)()>);
