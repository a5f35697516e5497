# robotd_warnings: the warning set every robotd target builds with.
add_library(robotd_warnings INTERFACE)
target_compile_options(robotd_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual -Wformat=2>
  $<$<BOOL:${ROBOTD_WERROR}>:-Werror>)
