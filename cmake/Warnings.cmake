# robotd_warnings: the warning set every robotd target builds with (C++, and C for the C API's
# example and tests).
add_library(robotd_warnings INTERFACE)
target_compile_options(robotd_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual -Wformat=2>
  $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wstrict-prototypes -Wmissing-prototypes -Wformat=2>
  $<$<BOOL:${ROBOTD_WERROR}>:-Werror>)
