# Sourced by scripts/sanitize and scripts/fuzz: configures a clang sanitizer build directory.
#
#   configure_sanitizer_build asan|tsan BUILD_DIR
#
# asan: AddressSanitizer + LeakSanitizer + UBSan, and the libFuzzer targets (ROBOTD_FUZZ), so
#       that one build serves both the sanitized suite and the fuzzers.
# tsan: ThreadSanitizer.
# clang rather than GCC: at -O1 with line tables it compiles an instrumented file in a third of
# GCC's time, and libFuzzer needs it anyway (docs/sanitizers.md).
configure_sanitizer_build() {
  local kind=$1 build_dir=$2 options
  case "$kind" in
    asan) options=(-DROBOTD_SANITIZE=address,undefined -DROBOTD_FUZZ=ON
                   -DROBOTD_FUZZ_SECONDS="${ROBOTD_FUZZ_SECONDS:-20}") ;;
    tsan) options=(-DROBOTD_SANITIZE=thread) ;;
    *) echo "configure_sanitizer_build: unknown kind '$kind' (expected asan or tsan)" >&2; return 2 ;;
  esac
  # A unity build, as CI's main stage (scripts/test).
  cmake -S . -B "$build_dir" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DROBOTD_WERROR=ON \
    -DCMAKE_UNITY_BUILD=ON "${options[@]}"
}
