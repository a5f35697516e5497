#!/usr/bin/env bash
# Run clang-tidy (with the repo's .clang-tidy, where every finding is an error) over the
# project's own .cpp files in compile_commands.json; fail on any finding.
#
#   run_clang_tidy.sh SOURCE_DIR BUILD_DIR [CLANG_TIDY]
#
# Own files: those under daemon/ clients/ drivers/ idl/ tests/ bench/ of SOURCE_DIR, which
# leaves out generated sources (BUILD_DIR and other build trees are not under those folders).
# Runs in parallel: run-clang-tidy of the same version when installed, else xargs -P$(nproc).
# Environment: JOBS overrides the job count, RUN_CLANG_TIDY names run-clang-tidy (empty: use
# xargs), ANALYZER_MODE sets the clang-analyzer checks' depth: shallow (default) or deep. Deep
# follows calls further and takes about twice as long in all (the analyzer alone: 7 s instead of
# 1.5 s for a driver file); shallow keeps lint.clang_tidy inside CI's time budget
# (docs/sanitizers.md, "CI").
set -euo pipefail

src=$(realpath "${1:?usage: $0 SOURCE_DIR BUILD_DIR [CLANG_TIDY]}")
build=$(realpath "${2:?usage: $0 SOURCE_DIR BUILD_DIR [CLANG_TIDY]}")
clang_tidy=${3:-${CLANG_TIDY:-clang-tidy}}
jobs=${JOBS:-$(nproc)}
analyzer_mode=${ANALYZER_MODE:-shallow}
[[ $analyzer_mode == shallow || $analyzer_mode == deep ]] ||
  { echo "FAIL: ANALYZER_MODE=$analyzer_mode: expected shallow or deep"; exit 1; }
analyzer_args=(-Xclang -analyzer-config -Xclang "mode=$analyzer_mode")
command -v "$clang_tidy" >/dev/null || { echo "SKIP: $clang_tidy not found" >&2; exit 77; }
[[ -f $build/compile_commands.json ]] ||
  { echo "FAIL: $build/compile_commands.json missing (configure with CMAKE_EXPORT_COMPILE_COMMANDS=ON)"; exit 1; }

# A unity build's compile_commands.json names its unity sources, not the project's files. Product
# code (daemon, clients, drivers, idl, bench) is then checked file by file, from a per-file database
# configured beside the build with the same compilers and flags (and its generated IDL headers,
# which the compile commands include): the clang static analyzer only looks into a file that is
# checked as itself. Test code, which the analyzer skips (tests/.clang-tidy), is checked through the
# build's own unity sources, with the tests' configuration: GoogleTest and the rest are parsed once
# per 8 files instead of once per file, a third of the time.
tidy_build=$build
unity_build=
if grep -q '/Unity/unity_' "$build/compile_commands.json"; then
  cache_value() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
  build_type=$(cache_value CMAKE_BUILD_TYPE)
  type_flags=$(tr '[:lower:]' '[:upper:]' <<<"$build_type")
  db=$build/lint-compile-db
  echo "unity build: configuring a per-file compile database in $db"
  cmake -S "$src" -B "$db" -DCMAKE_UNITY_BUILD=OFF -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
    -DCMAKE_C_COMPILER="$(cache_value CMAKE_C_COMPILER)" -DCMAKE_CXX_COMPILER="$(cache_value CMAKE_CXX_COMPILER)" \
    -DCMAKE_BUILD_TYPE="$build_type" -DROBOTD_WERROR="$(cache_value ROBOTD_WERROR)" \
    -DCMAKE_CXX_FLAGS_"$type_flags"="$(cache_value CMAKE_CXX_FLAGS_"$type_flags")" >"$db.log" 2>&1 &&
    cmake --build "$db" --target robotd_msgs_generated >>"$db.log" 2>&1 ||
    { cat "$db.log"; echo "FAIL: could not configure $db"; exit 1; }
  unity_build=$build
  tidy_build=$db
fi

# Prints the files to check from DATABASE's compile_commands.json: with MODE "files", the project's
# own .cpp files (not generated ones: those are under a build tree); "files-but-tests" leaves out
# tests/; "unity-tests" prints the unity sources of the targets under tests/.
list_files() {
  python3 - "$src" "$1" "$2" <<'PY'
import json, os, sys
src, build, mode = sys.argv[1], sys.argv[2], sys.argv[3]
own = ("daemon", "clients", "drivers", "idl", "tests", "bench")
seen = set()
for entry in json.load(open(os.path.join(build, "compile_commands.json"))):
    # Spelled as run-clang-tidy spells it, so its file regexes match.
    name = os.path.normpath(os.path.join(entry["directory"], entry["file"]))
    path = os.path.realpath(name)
    rel = os.path.relpath(path, src)
    if mode == "unity-tests":
        chosen = path.startswith(os.path.join(build, "tests") + os.sep) and "/Unity/unity_" in path and path.endswith(".cxx")
    else:
        top = rel.split(os.sep)[0]
        chosen = (path.endswith(".cpp") and not path.startswith(build + os.sep) and top in own
                  and not (mode == "files-but-tests" and top == "tests"))
    if chosen and os.path.exists(path) and name not in seen:
        seen.add(name)
        print(name)
PY
}

unity_tests=()
if [[ -n $unity_build ]]; then
  mapfile -t files < <(list_files "$tidy_build" files-but-tests)
  mapfile -t unity_tests < <(list_files "$unity_build" unity-tests)
else
  mapfile -t files < <(list_files "$tidy_build" files)
fi
((${#files[@]} + ${#unity_tests[@]} > 0)) || { echo "no project .cpp files in $build/compile_commands.json"; exit 0; }
"$clang_tidy" --version | grep -i version
echo "clang-tidy: ${#files[@]} files and ${#unity_tests[@]} unity sources of tests, $jobs jobs, analyzer mode $analyzer_mode"

log=$(mktemp)
tests_config=$(mktemp)
trap 'rm -f "$log" "$tests_config"' EXIT
start=$SECONDS
rc=0
# The run-clang-tidy of clang-tidy's own version (clang-tidy-22: run-clang-tidy-22).
version_suffix=$(basename "$clang_tidy" | sed -nE 's/^clang-tidy(-[0-9]+)$/\1/p')
run_clang_tidy=${RUN_CLANG_TIDY-run-clang-tidy$version_suffix}

# Runs clang-tidy on FILES... with the compile database in DATABASE and the options in EXTRA (an
# array name: more clang-tidy options); appends what it prints to $log, sets rc on failure.
tidy() {
  local database=$1 extra_name=$2
  shift 2
  local -n extra=$extra_name
  (($# > 0)) || return 0
  if [[ -n $run_clang_tidy ]] && command -v "$run_clang_tidy" >/dev/null; then
    # File arguments are regular expressions; anchor each path exactly.
    local regexes
    mapfile -t regexes < <(printf '%s\n' "$@" | sed 's/[].[^$*+?(){}|\\]/\\&/g; s/.*/^&$/')
    "$run_clang_tidy" -quiet -clang-tidy-binary "$(command -v "$clang_tidy")" -p "$database" -j "$jobs" \
      "${analyzer_args[@]/#/-extra-arg=}" "${extra[@]/#/-}" "${regexes[@]}" >>"$log" 2>&1 || rc=$?
  else
    printf '%s\0' "$@" |
      xargs -0 -n 1 -P "$jobs" "$clang_tidy" --quiet -p "$database" "${analyzer_args[@]/#/--extra-arg=}" \
        "${extra[@]/#/--}" >>"$log" 2>&1 || rc=$?
  fi
}

no_options=()
tidy "$tidy_build" no_options "${files[@]}"
if ((${#unity_tests[@]} > 0)); then
  # The tests' configuration as clang-tidy resolves it for a test file, but for the #include of
  # .cpp files, which is what a unity source is.
  "$clang_tidy" --dump-config "$src/tests/support/robotd_process.cpp" 2>/dev/null |
    sed -E 's/^(Checks: +"[^"]*)"/\1,-bugprone-suspicious-include"/' >"$tests_config"
  grep -q -- '-bugprone-suspicious-include"' "$tests_config" ||
    { echo "FAIL: could not derive the tests' clang-tidy configuration"; cat "$tests_config"; exit 1; }
  tests_options=("config-file=$tests_config")
  tidy "$unity_build" tests_options "${unity_tests[@]}"
fi

# run-clang-tidy forces --use-color; keep the log plain for CTest.
sed -i -E 's/\x1b\[[0-9;]*m//g' "$log"

# Findings are "file:line:col: error|warning: message [check]" lines plus their context.
if ((rc != 0)) || grep -qE ': (error|warning): ' "$log"; then
  # Drop run-clang-tidy's echo of each command line and clang-tidy's counters.
  awk -v ct="$(command -v "$clang_tidy") " 'index($0, ct) != 1' "$log" |
    grep -vE '^([0-9]+ warnings? (and [0-9]+ errors? )?generated|Suppressed [0-9]+ warnings|Use -header-filter)' || true
  echo "FAIL: clang-tidy findings ($((SECONDS - start)) s, exit $rc):"
  grep -E '^[^:]+:[0-9]+:[0-9]+: (error|warning): ' "$log" | sort -u | sed 's/^/  /' || true
  exit 1
fi
echo "ok: ${#files[@]} files and ${#unity_tests[@]} unity sources of tests clean ($((SECONDS - start)) s)"
