# ROBOTD_SANITIZE: build every target (libraries, the robotd executable, the driver plugins it
# dlopens, the simulators, the clients and the tests) with the given sanitizers:
#   ""                     no sanitizer (default)
#   "address,undefined"    AddressSanitizer + LeakSanitizer + UndefinedBehaviorSanitizer
#   "thread"               ThreadSanitizer
# Undefined behaviour aborts (-fno-sanitize-recover), so a test that hits it fails. scripts/sanitize
# configures build-asan and build-tsan this way and runs the suite; docs/sanitizers.md.
#
# The flags are directory-wide compile and link options, so every target of the tree gets them,
# MODULE plugins included. With GCC (the default compiler) the sanitizer runtimes are shared
# libraries the robotd executable loads first, and a dlopen'ed plugin uses the same runtime.
set(ROBOTD_SANITIZE "" CACHE STRING
    "Sanitizers to build with: empty, address,undefined or thread (docs/sanitizers.md)")
set_property(CACHE ROBOTD_SANITIZE PROPERTY STRINGS "" "address,undefined" "thread")

if(NOT ROBOTD_SANITIZE)
  return()
endif()
if(NOT ROBOTD_SANITIZE MATCHES "^(address,undefined|undefined,address|address|undefined|thread)$")
  message(FATAL_ERROR "ROBOTD_SANITIZE=${ROBOTD_SANITIZE}: expected empty, address,undefined or thread")
endif()
if(ROBOTD_FUZZ AND ROBOTD_SANITIZE STREQUAL "thread")
  message(FATAL_ERROR "ROBOTD_FUZZ builds with AddressSanitizer, which ThreadSanitizer cannot join: "
                      "use ROBOTD_SANITIZE=address,undefined (or empty) with ROBOTD_FUZZ")
endif()

add_compile_options(-fsanitize=${ROBOTD_SANITIZE} -fno-omit-frame-pointer)
# Reports need files and lines, not variables, and -O1 keeps stack traces whole: together they
# halve the build (GCC at -O2 -g takes 16 s for an end-to-end test file under ASan, clang at
# -O1 with line tables 6 s). They come after the build type's -O2 -g, so they win.
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  add_compile_options(-O1 -gline-tables-only)
else()
  add_compile_options(-O1 -g1)
endif()
add_link_options(-fsanitize=${ROBOTD_SANITIZE})
if(ROBOTD_SANITIZE MATCHES "undefined")
  add_compile_options(-fno-sanitize-recover=undefined)
endif()

# GCC 12 with -fsanitize=address reports -Wmaybe-uninitialized inside libstdc++'s <regex>
# (std::function members of a std::__detail::_State, used by config.cpp): a known false positive
# (GCC bug 105562) that ASan's instrumentation brings out. Sanitizer builds turn that one warning
# off; the ordinary -Werror build keeps checking it.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(robotd_warnings INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-Wno-maybe-uninitialized>)
endif()
