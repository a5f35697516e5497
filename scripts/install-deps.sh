#!/usr/bin/env bash
# Install the Debian (bookworm) packages robotd needs to build, test and run.
#
#   scripts/install-deps.sh
#
# Installs only what is missing (checked with dpkg-query), so it is quick and safe to re-run;
# apt-get update runs only when something is missing. Uses sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  cyclonedds-dev cyclonedds-tools
  libeigen3-dev libspdlog-dev nlohmann-json3-dev libsystemd-dev libcli11-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  rt-tests python3 systemd
  clang-format clang-tidy valgrind
  clang libclang-rt-14-dev
)

missing=()
for pkg in "${packages[@]}"; do
  if [[ $(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null) != installed ]]; then
    missing+=("$pkg")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo=()
if ((EUID != 0)); then
  command -v sudo >/dev/null || { echo "install-deps: not root and no sudo; install as root: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi

echo "install-deps: installing ${missing[*]}"
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
