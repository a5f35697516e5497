/* Compiled only: robotd/robotd.h is strict ISO C99 (-std=c99 -pedantic-errors), and its enums
 * are 32 bits wide, as C++ sees them (int32_t). */
#include <robotd/robotd.h>

typedef char robotd_enums_are_32_bits[sizeof(robotd_status) == 4 && sizeof(robotd_control_mode) == 4 ? 1 : -1];

robotd_status robotd_header_compiles_as_c99(void);
robotd_status robotd_header_compiles_as_c99(void) { return ROBOTD_OK; }
