#!/usr/bin/env bash
# Apply a sysusers.d file to a scratch root (copies of this machine's passwd/group) and check
# that USER exists and is a member of each GROUP.
#
#   sysusers_apply.sh CONF USER GROUP...
set -euo pipefail
conf=$1 user=$2
shift 2

command -v systemd-sysusers >/dev/null || { echo "systemd-sysusers not found (apt-get install systemd)" >&2; exit 1; }

root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
mkdir -p "$root/etc"
cp /etc/passwd /etc/group "$root/etc/"

systemd-sysusers --root="$root" "$(realpath "$conf")"

grep -q "^$user:" "$root/etc/passwd" || { echo "FAIL: user $user not created" >&2; exit 1; }
for group in "$@"; do
  members=$(awk -F: -v g="$group" '$1 == g { print $4 }' "$root/etc/group")
  [[ ,$members, == *",$user,"* ]] || { echo "FAIL: $user is not in group $group ($members)" >&2; exit 1; }
done
echo "ok: $conf creates $user in: $*"
