#!/usr/bin/env bash
# Fuzzes one target for a bounded time: the fuzz.<name> tests (label fuzz) of a ROBOTD_FUZZ
# build. The fuzzer starts from a fresh copy of the checked-in corpus in WORK_DIR/corpus and
# adds what it finds there, never in the source tree; an input that crashes, hangs or runs out
# of memory is saved as WORK_DIR/artifacts/<kind>-<sha1>, to be moved into the target's
# regressions/ once fixed (docs/fuzzing.md).
#
#   run_fuzzer.sh FUZZER CORPUS_DIR WORK_DIR SECONDS [LIBFUZZER_OPTIONS...]
set -euo pipefail

fuzzer=${1:?usage: $0 FUZZER CORPUS_DIR WORK_DIR SECONDS [LIBFUZZER_OPTIONS...]}
corpus=${2:?}
work=${3:?}
seconds=${4:?}
shift 4

rm -rf "$work/corpus"
mkdir -p "$work/artifacts"
cp -r "$corpus" "$work/corpus"
# -timeout: one input running this long is a hang (a decoder takes microseconds).
exec "$fuzzer" "$work/corpus" -max_total_time="$seconds" -timeout=10 -error_exitcode=1 -timeout_exitcode=1 \
  -print_final_stats=1 -artifact_prefix="$work/artifacts/" "$@"
