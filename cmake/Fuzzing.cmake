# ROBOTD_FUZZ: a libFuzzer build (clang only; scripts/fuzz configures one). Every target is
# compiled with libFuzzer's coverage instrumentation, AddressSanitizer and
# UndefinedBehaviorSanitizer, and undefined behaviour aborts so that the fuzzer reports it;
# tests/fuzz links the fuzzers and registers their fuzz tests. docs/fuzzing.md.
if(NOT ROBOTD_FUZZ)
  return()
endif()
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang" OR NOT CMAKE_C_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "ROBOTD_FUZZ needs clang (libFuzzer); this build uses ${CMAKE_C_COMPILER_ID} and "
                      "${CMAKE_CXX_COMPILER_ID}. Configure a new build directory with -DCMAKE_C_COMPILER=clang "
                      "-DCMAKE_CXX_COMPILER=clang++, or run scripts/fuzz.")
endif()
if(NOT ROBOTD_BUILD_TESTS)
  message(FATAL_ERROR "ROBOTD_FUZZ needs ROBOTD_BUILD_TESTS (the fuzzers live in tests/fuzz)")
endif()
# Crash reports need files and lines, not variables: -gline-tables-only compiles a third faster.
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                    -fno-omit-frame-pointer -gline-tables-only)
add_link_options(-fsanitize=address,undefined)
