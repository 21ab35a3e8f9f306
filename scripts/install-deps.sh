#!/usr/bin/env bash
# Installs the Debian packages mdhd builds and tests with. Idempotent and
# non-interactive: packages already present are not fetched again.
set -euo pipefail
packages=(build-essential cmake pkg-config clang libclang-rt-14-dev
  libmodbus-dev libglm-dev nlohmann-json3-dev libcpp-httplib-dev
  libgtest-dev libgmock-dev libbenchmark-dev libsqlite3-dev sqlite3 wrk
  python3-pymodbus python3-serial python3-serial-asyncio
  systemd curl nodejs chromium)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# npm: Debian's package, unless the installed nodejs brings its own (NodeSource's
# nodejs includes npm and conflicts with Debian's npm package).
command -v npm >/dev/null 2>&1 || missing+=(npm)
if ((${#missing[@]})); then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  echo "install-deps: installing ${missing[*]}" >&2
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi
