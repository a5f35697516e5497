#!/usr/bin/env bash
# Install the Debian (bookworm) packages robotd needs to build, test and run.
#
#   scripts/install-deps.sh                  what building, testing and running need
#   scripts/install-deps.sh --conformance    also what the conformance generators need to run
#                                            the vendors' own code (docs/conformance.md)
#
# Installs only what is missing (checked with dpkg-query), so it is quick and safe to re-run;
# apt-get update runs only when something is missing. Uses sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  cyclonedds-dev cyclonedds-tools
  libeigen3-dev libspdlog-dev nlohmann-json3-dev libsystemd-dev libcli11-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  rt-tests python3 python3-matplotlib systemd
  clang-format clang-tidy valgrind
  clang libclang-rt-14-dev
)

# Only for regenerating the conformance data from the vendors' code; CI replays the recorded data.
if [[ ${1:-} == --conformance ]]; then
  packages+=(python3-can python3-serial python3-numpy)
elif (($# > 0)); then
  echo "install-deps: unknown argument '$1' (expected nothing or --conformance)" >&2
  exit 2
fi

# Installed when the archive has them (clang-tidy-22 comes from bookworm-security): lint runs
# three times faster with it and falls back to clang-tidy (14) without it.
optional=(clang-tidy-22)

installed() { [[ $(dpkg-query -W -f='${db:Status-Status}' "$1" 2>/dev/null) == installed ]]; }
missing=()
for pkg in "${packages[@]}"; do installed "$pkg" || missing+=("$pkg"); done
missing_optional=()
for pkg in "${optional[@]}"; do installed "$pkg" || missing_optional+=("$pkg"); done

if ((${#missing[@]} + ${#missing_optional[@]} == 0)); then
  echo "install-deps: all $((${#packages[@]} + ${#optional[@]})) packages already installed"
  exit 0
fi

sudo=()
if ((EUID != 0)); then
  command -v sudo >/dev/null || { echo "install-deps: not root and no sudo; install as root: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi

"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
for pkg in "${missing_optional[@]}"; do
  if apt-cache show "$pkg" >/dev/null 2>&1; then
    missing+=("$pkg")
  else
    echo "install-deps: $pkg is not in the archive; going on without it"
  fi
done
((${#missing[@]} > 0)) || exit 0
echo "install-deps: installing ${missing[*]}"
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
