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

# A unity build's compile_commands.json names its unity sources, not the project's files: clang-tidy
# then reads a per-file database of its own, configured beside the build with the same compilers
# and flags (and its generated IDL headers, which the compile commands include).
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
  build=$db
fi

mapfile -t files < <(python3 - "$src" "$build" <<'PY'
import json, os, sys
src, build = sys.argv[1], sys.argv[2]
own = ("daemon", "clients", "drivers", "idl", "tests", "bench")
seen = set()
for entry in json.load(open(os.path.join(build, "compile_commands.json"))):
    # Spelled as run-clang-tidy spells it, so its file regexes match.
    name = os.path.normpath(os.path.join(entry["directory"], entry["file"]))
    path = os.path.realpath(name)
    rel = os.path.relpath(path, src)
    if (path.endswith(".cpp") and not path.startswith(build + os.sep) and rel.split(os.sep)[0] in own
            and os.path.exists(path) and name not in seen):
        seen.add(name)
        print(name)
PY
)
((${#files[@]} > 0)) || { echo "no project .cpp files in $build/compile_commands.json"; exit 0; }
"$clang_tidy" --version | grep -i version
echo "clang-tidy: ${#files[@]} files, $jobs jobs, analyzer mode $analyzer_mode"

log=$(mktemp)
trap 'rm -f "$log"' EXIT
start=$SECONDS
rc=0
# The run-clang-tidy of clang-tidy's own version (clang-tidy-22: run-clang-tidy-22).
version_suffix=$(basename "$clang_tidy" | sed -nE 's/^clang-tidy(-[0-9]+)$/\1/p')
run_clang_tidy=${RUN_CLANG_TIDY-run-clang-tidy$version_suffix}
if [[ -n $run_clang_tidy ]] && command -v "$run_clang_tidy" >/dev/null; then
  # File arguments are regular expressions; anchor each path exactly.
  mapfile -t regexes < <(printf '%s\n' "${files[@]}" | sed 's/[].[^$*+?(){}|\\]/\\&/g; s/.*/^&$/')
  "$run_clang_tidy" -quiet -clang-tidy-binary "$(command -v "$clang_tidy")" -p "$build" -j "$jobs" \
    "${analyzer_args[@]/#/-extra-arg=}" "${regexes[@]}" \
    >"$log" 2>&1 || rc=$?
else
  printf '%s\0' "${files[@]}" |
    xargs -0 -n 1 -P "$jobs" "$clang_tidy" --quiet -p "$build" "${analyzer_args[@]/#/--extra-arg=}" >"$log" 2>&1 ||
    rc=$?
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
echo "ok: ${#files[@]} files clean ($((SECONDS - start)) s)"
