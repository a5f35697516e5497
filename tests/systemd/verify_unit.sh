#!/usr/bin/env bash
# Verify systemd unit files with systemd-analyze verify.
#
#   verify_unit.sh UNIT...                         every UNIT must verify with no warning
#   verify_unit.sh --reject UNIT PATTERN ...       every UNIT must be rejected with PATTERN
#                                                  (grep -E) in what systemd-analyze prints
#
# systemd-analyze verify exits 0 on unit warnings (unknown keys, bad values) unless told
# otherwise; --recursive-errors=no makes any warning about the named unit fail it, while
# warnings about the host's own units (network-online.target, ...) are not ours to judge.
# It needs no systemd as PID 1, and a User= that does not exist on this machine is fine.
set -euo pipefail

usage() { echo "usage: $0 UNIT... | $0 --reject UNIT PATTERN [--reject UNIT PATTERN]..." >&2; exit 2; }
(($# > 0)) || usage
command -v systemd-analyze >/dev/null || { echo "systemd-analyze not found (apt-get install systemd)" >&2; exit 1; }

status=0
check() {  # check UNIT [PATTERN]: no PATTERN = must verify, PATTERN = must be rejected for it
  local unit=$1 pattern=${2:-} out rc=0
  [[ -f $unit ]] || { echo "FAIL: $unit: no such file"; status=1; return; }
  out=$(systemd-analyze verify --man=no --recursive-errors=no "$unit" 2>&1) || rc=$?
  if [[ -z $pattern ]]; then
    if ((rc != 0)) || [[ -n $out ]]; then
      echo "FAIL: $unit does not verify (exit $rc):"; status=1
      if grep -q 'is not executable: No such file' <<<"$out"; then
        echo "    (ExecStart names the build tree's robotd: build the robotd target before this test)"
      fi
    else
      echo "ok: $unit verifies"
    fi
  elif ((rc == 0)); then
    echo "FAIL: $unit is broken on purpose but verified (exit 0):"; status=1
  elif ! grep -Eq -- "$pattern" <<<"$out"; then
    echo "FAIL: $unit was rejected (exit $rc), but not for /$pattern/:"; status=1
  else
    echo "ok: $unit rejected as expected (exit $rc):"
  fi
  [[ -z $out ]] || sed 's/^/    /' <<<"$out"
}

if [[ $1 == --reject ]]; then
  while (($# > 0)); do
    [[ $1 == --reject && $# -ge 3 ]] || usage
    check "$2" "$3"
    shift 3
  done
else
  for unit in "$@"; do check "$unit"; done
fi
exit "$status"
