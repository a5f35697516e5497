/* Stand-in for the firmware's App/debug_print/debug_print.h (a UART printf): the host's stdio. */
#ifndef ROBOTD_CONFORMANCE_DEBUG_PRINT_H
#define ROBOTD_CONFORMANCE_DEBUG_PRINT_H
#include <stdio.h>
#endif
