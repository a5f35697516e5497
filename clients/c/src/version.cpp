#include "robotd/robotd.h"

#ifndef ROBOTD_VERSION
#error "ROBOTD_VERSION must be the project version (set by CMake)"
#endif

extern "C" {

int robotd_c_api_version(void) { return ROBOTD_C_API_VERSION; }

const char* robotd_version(void) { return ROBOTD_VERSION; }

}  // extern "C"
